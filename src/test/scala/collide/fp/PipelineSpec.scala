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
}
