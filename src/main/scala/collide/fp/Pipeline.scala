package collide.fp

import chisel3._
import chisel3.util._

/** Pipeline registers with a shared advance enable, so a whole datapath can stall as one
  * (the SCPU's valid/ready wraps it: en = !out.valid || out.ready).
  */
object Pipeline {
  /** `x` delayed by `n` registers, each loaded only when `en`. n = 0 is a wire. */
  def apply[T <: Data](x: T, n: Int, en: Bool): T =
    (0 until n).foldLeft(x)((acc, _) => RegEnable(acc, en))

  /** A valid bit delayed by `n` enabled registers that reset to false. */
  def valid(v: Bool, n: Int, en: Bool): Bool =
    (0 until n).foldLeft(v)((acc, _) => RegEnable(acc, false.B, en))

  /** Splits `latency` registers over `stages` stage boundaries, latest boundaries first
    * (a register at the output first, then before rounding, ...), so latency 1 registers
    * the output and larger latencies cut the datapath further back. Returns, per boundary
    * (0 = earliest), how many registers to place there.
    */
  def placement(latency: Int, stages: Int): Seq[Int] = {
    require(latency >= 0 && stages >= 1)
    val base = latency / stages
    val extra = latency % stages
    (0 until stages).map(i => base + (if (i >= stages - extra) 1 else 0))
  }

  /** Like placement, but for a chain of alike stages (an iterative core's iterations): fewer
    * registers than boundaries are spaced evenly, about one every stages / latency, the last at
    * the output, so the longest run of unregistered stages is as short as the latency allows
    * (placement would leave the first stages - latency of them as one combinational path).
    */
  def spread(latency: Int, stages: Int): Seq[Int] = {
    require(latency >= 0 && stages >= 1)
    if (latency >= stages) placement(latency, stages)
    else (0 until stages).map(i => if ((i + 1) * latency / stages > i * latency / stages) 1 else 0)
  }

  /** Where `latency` registers go in a datapath of segments whose estimated delays are
    * `delays` (segment i ends at boundary i; the last boundary is the output). The output gets
    * the first register, as in [[placement]]; the next ones go to the inner boundaries that
    * make the longest unregistered run (a sum of consecutive segments) as short as it can be,
    * so every register up to delays.size cuts a path. Past delays.size the extra registers
    * stack at the output, where they cut nothing. Returns the count per boundary.
    */
  def balanced(latency: Int, delays: Seq[Double]): Seq[Int] = {
    require(latency >= 0 && delays.nonEmpty && delays.forall(_ >= 0))
    val n = delays.size
    if (latency == 0) return Seq.fill(n)(0)
    val inner = math.min(latency - 1, n - 1)
    val cuts = bestCuts(delays, inner)
    (0 until n).map(i => if (i == n - 1) latency - inner else if (cuts(i)) 1 else 0)
  }

  /** The longest unregistered run left by [[balanced]] at `latency`: the datapath's estimated
    * critical path between registers (the input counted as registered). */
  def longestRun(latency: Int, delays: Seq[Double]): Double = {
    val regs = balanced(latency, delays)
    var run = 0.0; var worst = 0.0
    for ((d, r) <- delays.zip(regs)) { run += d; worst = math.max(worst, run); if (r > 0) run = 0.0 }
    worst
  }

  /** The smallest latency whose longest run fits `budget` (Right), or, when one segment alone
    * is longer, Left with that segment's delay: no placement reaches the clock. */
  def latencyFor(budget: Double, delays: Seq[Double]): Either[Double, Int] = {
    val worst = delays.max
    if (worst > budget) Left(worst)
    else Right((1 to delays.size).find(l => longestRun(l, delays) <= budget).get)
  }

  /** Which of the n - 1 inner boundaries get a register when `k` are placed: minimizes the
    * longest run (a linear partition), and among equal runs prefers later boundaries. */
  private def bestCuts(d: Seq[Double], k: Int): Seq[Boolean] = {
    val n = d.size
    val prefix = d.scanLeft(0.0)(_ + _)
    def run(i: Int, j: Int) = prefix(j) - prefix(i) // segments i until j
    // best(j)(c): the longest run over segments j until n with c cuts among boundaries j..n-2.
    val best = Array.fill(n + 1, k + 1)(Double.PositiveInfinity)
    val next = Array.fill(n + 1, k + 1)(-1)
    for (j <- n - 1 to 0 by -1; c <- 0 to k) {
      best(j)(c) = run(j, n); next(j)(c) = n
      if (c > 0) for (e <- n - 1 to j + 1 by -1) { // a cut after segment e - 1
        val v = math.max(run(j, e), best(e)(c - 1))
        if (v < best(j)(c) - 1e-9) { best(j)(c) = v; next(j)(c) = e }
      }
    }
    val cut = Array.fill(n)(false)
    var j = 0; var c = k
    while (j < n && c > 0 && next(j)(c) < n) { cut(next(j)(c) - 1) = true; j = next(j)(c); c -= 1 }
    // Cuts that shorten nothing (zero-delay segments) still go inside, latest boundaries first.
    for (b <- n - 2 to 0 by -1 if c > 0 && !cut(b)) { cut(b) = true; c -= 1 }
    cut.toSeq
  }
}
