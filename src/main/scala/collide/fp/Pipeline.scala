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
}
