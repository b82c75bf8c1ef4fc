package collide.world

import chisel3._
import chiseltest._

/** Runs one world through a BroadPhase: starts it, serves its sphere table on every lane's
  * port (one cycle of read latency, as a block RAM) and takes a pair from each lane whenever
  * `ready()` allows, until busy falls. Returns the pairs in the order taken (lane order within
  * a cycle) and the cycles from start; after `maxCycles` it gives the pairs so far to `stuck`,
  * which must not return.
  *
  * With `fed` (the BroadPhase's feed ports, as the AFU's table writes drive them), the world
  * begins first and its spheres arrive on the feed a line of `feed.length` consecutive spheres a
  * cycle, the lines in a random order with random idle cycles between them (a link returns
  * lines out of order), the last line partly empty; start follows once all are in. */
object BroadPhaseDriver {
  /** Feeds the table through the feed ports in shuffled lines; returns the cycles it took. */
  private def feedTable(dut: BroadPhase, table: IndexedSeq[Seq[BigInt]], rng: scala.util.Random): Long = {
    val width = dut.io.feed.length
    dut.io.num.poke(table.length.U)
    dut.io.begin.poke(true.B); dut.clock.step(); dut.io.begin.poke(false.B)
    var cycles = 1L
    for (line <- rng.shuffle((0 until (table.length + width - 1) / width).toList)) {
      while (rng.nextInt(4) == 0) { dut.clock.step(); cycles += 1 }
      for ((f, s) <- dut.io.feed.zipWithIndex) {
        val at = line * width + s
        f.valid.poke((at < table.length).B)
        if (at < table.length) table(at).zipWithIndex.foreach { case (b, c) => f.bits(c).poke(b.U) }
      }
      dut.clock.step(); cycles += 1
      dut.io.feed.foreach(_.valid.poke(false.B))
    }
    cycles
  }

  /** As above; with `fed`, also the cycles the feed took (from begin to start). */
  def run(dut: BroadPhase, table: IndexedSeq[Seq[BigInt]], ready: () => Boolean, maxCycles: Long,
          fed: Option[scala.util.Random] = None)
         (stuck: Seq[(Int, Int)] => Nothing): (Seq[(Int, Int)], Long, Long) = {
    dut.io.begin.poke(false.B)
    dut.io.feed.foreach(_.valid.poke(false.B))
    val feedCycles = fed.map(rng => feedTable(dut, table, rng)).getOrElse(0L)
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
    (pairs.toSeq, cycles, feedCycles)
  }
}
