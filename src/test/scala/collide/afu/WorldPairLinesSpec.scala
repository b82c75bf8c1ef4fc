package collide.afu

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.testutil.Seeds

/** WorldPairLines alone (treadle): the lanes' candidates, offered at random under random
  * back-pressure on the lines, come out in pair lines exactly as the host lays out a pair list:
  * every candidate once, a cycle's candidates in lane order after those taken before, lines
  * numbered from 0, a line's unused slots zero, and `emitted` the candidates in the lines out.
  * With more lanes than a line has slots (32), every lane waits while the buffer has no room
  * for all of them. */
class WorldPairLinesSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "WorldPairLines"
  // 32 lanes on Verilator (treadle took 25-45 s a case); fewer lanes run quicker on treadle
  // than a Verilator build takes.
  private val verilator = Seq(chiseltest.simulator.VerilatorBackendAnnotation)

  private val itemW = 12
  private def params(lanes: Int) =
    PucParams(scpus = 16, linkWidth = 32, scpuTagBits = 24, scpuLatency = 3, maxSpheres = 4096,
      maxReads = 16, maxWrites = 8, tagBits = 6, name = s"_wpl$lanes")

  /** Offers `perLane` candidates from each lane (lane l's k-th is (k, 64 l + k)) with random
    * gaps, takes lines with random stalls, and checks the lines against the order the
    * candidates were taken in. */
  def soak(lanes: Int, perLane: Int, offer: Double, take: Double): Unit = {
    val p = params(lanes)
    val ppl = p.layout.pairsPerLine
    val rnd = Seeds.rng(s"WorldPairLinesSpec-l$lanes-o$offer-t$take")
    test(new WorldPairLines(p, itemW, lanes)).withAnnotations(if (lanes >= 32) verilator else Seq()) { dut =>
      dut.clock.setTimeout(0)
      dut.io.start.poke(true.B); dut.clock.step(); dut.io.start.poke(false.B)
      val next = Array.fill(lanes)(0)
      val taken = collection.mutable.ArrayBuffer.empty[(Int, Int)]
      val lines = collection.mutable.ArrayBuffer.empty[(BigInt, BigInt)]
      var maxWait = 0
      val waiting = Array.fill(lanes)(0)
      var cycles = 0
      def allOffered = next.forall(_ == perLane)
      while (!(allOffered && dut.io.idle.peek().litToBoolean) && cycles < 200000) {
        val offers = (0 until lanes).map(l => next(l) < perLane && (waiting(l) > 0 || rnd.nextDouble() < offer))
        for (l <- 0 until lanes) {
          dut.io.in(l).valid.poke(offers(l).B)
          dut.io.in(l).bits.i.poke(next(l).U)
          dut.io.in(l).bits.j.poke((64 * l + next(l)).U)
        }
        dut.io.done.poke(allOffered.B)
        val ready = rnd.nextDouble() < take
        dut.io.out.ready.poke(ready.B)
        if (ready && dut.io.out.valid.peek().litToBoolean)
          lines += ((dut.io.out.bits.line.peek().litValue, dut.io.out.bits.data.peek().litValue))
        for (l <- 0 until lanes if offers(l)) {
          if (dut.io.in(l).ready.peek().litToBoolean) {
            taken += ((next(l), 64 * l + next(l))); next(l) += 1; waiting(l) = 0
          } else { waiting(l) += 1; maxWait = maxWait max waiting(l) }
        }
        dut.clock.step(); cycles += 1
      }
      assert(allOffered && dut.io.idle.peek().litToBoolean, s"$lanes lanes: not drained after $cycles cycles")
      val n = lanes * perLane
      assert(taken.length == n)
      assert(dut.io.emitted.peek().litValue == n, s"emitted ${dut.io.emitted.peek().litValue}, want $n")
      assert(lines.length == (n + ppl - 1) / ppl, s"${lines.length} lines for $n candidates")
      for (((num, data), k) <- lines.zipWithIndex) {
        assert(num == k, s"line $k numbered $num")
        for (s <- 0 until ppl) {
          val word = (data >> (32 * s)) & 0xffffffffL
          val c = k * ppl + s
          val want = if (c < n) BigInt(taken(c)._1) | (BigInt(taken(c)._2) << 16) else BigInt(0)
          assert(word == want, s"$lanes lanes: line $k slot $s is 0x${word.toString(16)}, want 0x${want.toString(16)}")
        }
      }
      println(s"[WorldPairLinesSpec] $lanes lanes: $n candidates in ${lines.length} lines, $cycles cycles, a lane waited at most $maxWait")
    }
  }

  it should "pack one lane's candidates into lines in order" in soak(1, 40, 0.7, 0.6)

  it should "pack 16 lanes' candidates, a cycle's in lane order, under back-pressure" in soak(16, 12, 0.5, 0.5)

  it should "let 32 lanes offer at once, all of them waiting while the buffer lacks room for every lane" in soak(32, 10, 0.9, 0.8)

  it should "pack sparse candidates from 32 lanes and flush the last part-full line" in soak(32, 3, 0.1, 0.9)
}
