package collide.world

import chisel3._
import chiseltest._

/** Runs one world through a BroadPhase: starts it, serves its sphere table (one cycle of
  * read latency, as a block RAM) and takes a pair in each cycle `ready()` allows, until busy
  * falls. Returns the pairs in order and the cycles from start; after `maxCycles` it gives
  * the pairs so far to `stuck`, which must not return. */
object BroadPhaseDriver {
  def run(dut: BroadPhase, table: IndexedSeq[Seq[BigInt]], ready: () => Boolean, maxCycles: Long)
         (stuck: Seq[(Int, Int)] => Nothing): (Seq[(Int, Int)], Long) = {
    dut.io.num.poke(table.length.U)
    dut.io.start.poke(true.B); dut.clock.step(); dut.io.start.poke(false.B)
    val pairs = scala.collection.mutable.ArrayBuffer.empty[(Int, Int)]
    var cycles = 1L
    while (dut.io.busy.peek().litToBoolean) {
      val addr = dut.io.sphere.addr.peek().litValue.toInt
      val take = ready()
      dut.io.pairs.ready.poke(take.B)
      if (take && dut.io.pairs.valid.peek().litToBoolean)
        pairs += ((dut.io.pairs.bits.i.peek().litValue.toInt, dut.io.pairs.bits.j.peek().litValue.toInt))
      dut.clock.step(); cycles += 1
      val data = if (addr < table.length) table(addr) else Seq.fill(4)(BigInt(0))
      data.zipWithIndex.foreach { case (b, f) => dut.io.sphere.data(f).poke(b.U) }
      if (cycles > maxCycles) stuck(pairs.toSeq)
    }
    (pairs.toSeq, cycles)
  }
}
