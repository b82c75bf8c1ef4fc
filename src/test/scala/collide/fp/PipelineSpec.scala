package collide.fp

import org.scalatest.flatspec.AnyFlatSpec

/** Where the FP units put their pipeline registers (pure Scala: no hardware is built). */
class PipelineSpec extends AnyFlatSpec {
  behavior of "Pipeline.spread"

  /** The longest run of boundaries without a register, the output's included. */
  private def longestBare(regs: Seq[Int]): Int = regs.foldLeft((0, 0)) { case ((run, most), r) =>
    if (r > 0) (0, most) else (run + 1, math.max(most, run + 1))
  }._2

  it should "place exactly the latency, the last at the output, and leave no run of bare boundaries longer than stages / latency" in {
    for (stages <- 1 to 60; latency <- 1 to stages) {
      val regs = Pipeline.spread(latency, stages)
      assert(regs.sum == latency, s"latency $latency over $stages")
      assert(regs.last >= 1, s"latency $latency over $stages: no register at the output")
      // Each stage holds at most ceil(stages / latency) iterations.
      val most = (stages + latency - 1) / latency
      assert(longestBare(regs) <= most - 1, s"latency $latency over $stages: $regs")
    }
  }

  it should "be placement's split where there are at least as many registers as boundaries, and none at latency 0" in {
    for (stages <- 1 to 30; latency <- stages to 3 * stages)
      assert(Pipeline.spread(latency, stages) == Pipeline.placement(latency, stages))
    assert(Pipeline.spread(0, 24) == Seq.fill(24)(0))
  }

  it should "spread five registers over 24 iterations one every four or five, where placement put all five at the end" in {
    assert(Pipeline.spread(5, 24).zipWithIndex.collect { case (1, i) => i } == Seq(4, 9, 14, 19, 23))
    assert(Pipeline.placement(5, 24).zipWithIndex.collect { case (1, i) => i } == Seq(19, 20, 21, 22, 23))
  }

  behavior of "Pipeline.balanced"

  it should "register the output first, then the inner boundaries that shorten the longest run most" in {
    val d = Seq(1.0, 5.0, 1.0, 1.0, 4.0)
    assert(Pipeline.balanced(0, d) == Seq(0, 0, 0, 0, 0))
    assert(Pipeline.balanced(1, d) == Seq(0, 0, 0, 0, 1))
    assert(Pipeline.balanced(2, d) == Seq(0, 1, 0, 0, 1))       // runs 6 and 6
    assert(Pipeline.balanced(3, d) == Seq(0, 1, 0, 1, 1))       // 6, 2, 4: 6 is the first stage's
    assert(Pipeline.balanced(5, d) == Seq(1, 1, 1, 1, 1))
    assert(Pipeline.balanced(7, d) == Seq(1, 1, 1, 1, 3))       // past the boundaries: at the output
    assert(Pipeline.longestRun(2, d) == 6.0 && Pipeline.longestRun(5, d) == 5.0)
  }

  it should "never lengthen the longest run as the latency grows, and place exactly the latency" in {
    val rng = new scala.util.Random(20261206)
    for (_ <- 0 until 300) {
      val d = Seq.fill(1 + rng.nextInt(12))(rng.nextInt(5000).toDouble)
      val runs = (1 to d.size + 2).map(l => Pipeline.longestRun(l, d))
      assert(runs.zip(runs.tail).forall { case (a, b) => b <= a }, s"$d: $runs")
      for (l <- 0 to d.size + 2) assert(Pipeline.balanced(l, d).sum == l)
      // The linear partition's optimum: no other choice of l - 1 inner cuts does better.
      for (l <- 1 to math.min(d.size, 4)) {
        val best = (0 until d.size - 1).combinations(l - 1).map { cuts =>
          val bounds = (-1 +: cuts :+ (d.size - 1))
          bounds.zip(bounds.tail).map { case (a, b) => d.slice(a + 1, b + 1).sum }.max
        }.min
        assert(Pipeline.longestRun(l, d) == best, s"$d at latency $l")
      }
    }
  }

  it should "give the smallest latency whose runs fit a budget, or the stage that cannot fit" in {
    val d = Seq(1.0, 5.0, 1.0, 1.0, 4.0)
    assert(Pipeline.latencyFor(6.0, d) == Right(2))
    assert(Pipeline.latencyFor(5.0, d) == Right(4))
    assert(Pipeline.latencyFor(4.5, d) == Left(5.0))
  }
}
