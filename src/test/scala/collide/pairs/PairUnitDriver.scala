package collide.pairs

import scala.util.Random
import chisel3._
import chiseltest._

/** How SpherePlaneSpec and CapsuleSphereSpec drive a pair unit (one enable, Valid in and out,
  * a tag carried through): the hard cases back to back with the enable high, each result
  * checked exactly `latency` cycles after its pair; then every pair with a quarter of the
  * cycles stalled (enable low) and a tenth of the inputs empty, results checked in order. */
object PairUnitDriver {
  /** `poke(k)` drives pair k's fields and tag; `tag()` reads the output's tag; `check(k)`
    * compares the output with pair k's expected result. Returns the cycles of the second phase. */
  def run(clock: Clock, en: Bool, inValid: Bool, outValid: Bool, latency: Int, hard: Int, n: Int, rng: Random,
          what: String)(poke: Int => Unit, tag: () => Int, check: Int => Unit): Int = {
    en.poke(true.B)
    for (t <- 0 until hard + latency) {
      inValid.poke((t < hard).B)
      if (t < hard) poke(t)
      if (t >= latency) { outValid.expect(true.B); check(t - latency) } else outValid.expect(false.B)
      clock.step()
    }
    outValid.expect(false.B)
    var next = 0
    var seen = 0
    var cycles = 0
    while (seen < n && cycles < 4 * n + 1000) {
      val on = rng.nextInt(4) != 0
      en.poke(on.B)
      val send = on && next < n && rng.nextInt(10) != 0
      inValid.poke(send.B)
      if (send) poke(next)
      if (on && outValid.peek().litToBoolean) {
        val k = tag()
        assert(k == seen, s"$what: result for pair $k where pair $seen was due")
        check(k)
        seen += 1
      }
      if (send) next += 1
      clock.step()
      cycles += 1
    }
    assert(seen == n, s"$what: $seen of $n results in $cycles cycles")
    cycles
  }
}
