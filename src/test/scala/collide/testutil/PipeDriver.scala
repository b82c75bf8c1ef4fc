package collide.testutil

import scala.collection.mutable
import scala.util.Random

/** Streams vectors 0 until n through a fully pipelined DUT, a new one every cycle, and
  * checks each result exactly `latency` enabled cycles later. The harness keeps its own
  * shift register of which vector should be at the output, so it checks the valid bit's
  * timing (bubbles: valid low on some inputs) and, with `stalls`, that en low holds the
  * pipeline (outputs stay, the input is ignored: a different vector is poked meanwhile).
  *
  * Callbacks: setEn(en); poke(Some(i)) drives vector i with valid high, poke(None) drives
  * valid low; outValid() peeks out.valid; check(i) peeks the outputs and asserts they are
  * vector i's expected result; step() advances one clock.
  */
object PipeDriver {
  def run(latency: Int, n: Int, rng: Random, stalls: Boolean)(
      setEn: Boolean => Unit, poke: Option[Int] => Unit, outValid: () => Boolean,
      check: Int => Unit, step: () => Unit): Int = {
    val inflight = mutable.Queue.fill(latency)(Option.empty[Int]) // head = at the output
    var next = 0
    var cycle = 0
    while (next < n || inflight.exists(_.isDefined)) {
      val en = !stalls || rng.nextInt(4) != 0
      val v  = next < n && rng.nextInt(10) != 0
      setEn(en)
      if (latency > 0 && !en) poke(if (v) Some(rng.nextInt(n)) else None) // must be ignored
      else poke(if (v) Some(next) else None)
      val expected = if (latency == 0) (if (v) Some(next) else None) else inflight.head
      val ov = outValid()
      assert(ov == expected.isDefined,
        s"cycle $cycle: out.valid = $ov, expected ${expected.isDefined} (vector ${expected.getOrElse("-")}, latency $latency, en $en)")
      expected.foreach(check)
      if (latency == 0) { if (v) next += 1 }
      else if (en) {
        inflight.dequeue()
        inflight.enqueue(if (v) Some(next) else None)
        if (v) next += 1
      }
      step()
      cycle += 1
    }
    cycle
  }
}

/** The configurations a two-operand FP operator's RTL spec streams through: every preset with
  * subnormals kept and flushed, each format at latency 0 and at its full pipeline (3), the two
  * alternating between the subnormal settings; plus the spec's own extra cases. */
object FpRtlMatrix {
  import collide.fp.{FloatFormat, FpParams}
  def configs(extra: (FpParams, Int)*): Seq[(FpParams, Int)] =
    FloatFormat.presets.map(_._2).zipWithIndex.flatMap { case (f, i) =>
      Seq((FpParams(f), if (i % 2 == 0) 0 else 3), (FpParams(f, subnormals = false), if (i % 2 == 0) 3 else 0))
    } ++ extra
}
