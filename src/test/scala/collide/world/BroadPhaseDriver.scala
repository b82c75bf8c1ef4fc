package collide.world

import chisel3._
import chiseltest._

/** Runs one world through a BroadPhase: starts it, serves its sphere table on every lane's
  * port (one cycle of read latency, as a block RAM) and takes a pair from each lane whenever
  * `ready()` allows, until busy falls. Returns the pairs in the order taken (lane order within
  * a cycle) and the cycles from start; after `maxCycles` it gives the pairs so far to `stuck`,
  * which must not return. */
object BroadPhaseDriver {
  def run(dut: BroadPhase, table: IndexedSeq[Seq[BigInt]], ready: () => Boolean, maxCycles: Long)
         (stuck: Seq[(Int, Int)] => Nothing): (Seq[(Int, Int)], Long) = {
    dut.io.num.poke(table.length.U)
    dut.io.start.poke(true.B); dut.clock.step(); dut.io.start.poke(false.B)
    val pairs = scala.collection.mutable.ArrayBuffer.empty[(Int, Int)]
    var cycles = 1L
    while (dut.io.busy.peek().litToBoolean) {
      val addrs = dut.io.sphere.map(_.addr.peek().litValue.toInt)
      for (port <- dut.io.pairs) {
        val take = ready()
        port.ready.poke(take.B)
        if (take && port.valid.peek().litToBoolean)
          pairs += ((port.bits.i.peek().litValue.toInt, port.bits.j.peek().litValue.toInt))
      }
      dut.clock.step(); cycles += 1
      for ((addr, port) <- addrs.zip(dut.io.sphere)) {
        val data = if (addr < table.length) table(addr) else Seq.fill(4)(BigInt(0))
        data.zipWithIndex.foreach { case (b, f) => port.data(f).poke(b.U) }
      }
      if (cycles > maxCycles) stuck(pairs.toSeq)
    }
    (pairs.toSeq, cycles)
  }
}
