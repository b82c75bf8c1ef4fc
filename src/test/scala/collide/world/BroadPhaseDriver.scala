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
  * lines out of order), the last line partly empty; start follows once all are in. With
  * `ahead`, the next world is begun and fed so while this one runs, as the AFU's run queue does. */
object BroadPhaseDriver {
  /** A world's table fed through the feed ports: begin once the broad phase can take it, then
    * the lines in a shuffled order with random idle cycles between them, a line a `step`. As the
    * AFU's run queue does, it may be fed while the world before it runs (`run`'s `ahead`). */
  final class Feeder(dut: BroadPhase, val table: IndexedSeq[Seq[BigInt]], rng: scala.util.Random) {
    private val width = dut.io.feed.length
    private var lines = rng.shuffle((0 until (table.length + width - 1) / width).toList)
    /** The begin was taken, and while the world before it was busy. */
    var begun = false
    var begunAhead = false
    /** Cycles from the later of the begin and the world before it going idle, to now: the
      * counters' clear runs in them. */
    var clearCycles = 0L
    def done: Boolean = begun && lines.isEmpty
    /** Drives this cycle's inputs (begin, or a line or nothing) and steps the clock. */
    def step(): Unit = {
      val busy = dut.io.busy.peek().litToBoolean
      dut.io.begin.poke(false.B)
      dut.io.feed.foreach(_.valid.poke(false.B))
      if (!begun) {
        if (dut.io.canBegin.peek().litToBoolean) {
          dut.io.num.poke(table.length.U); dut.io.begin.poke(true.B)
          begun = true; begunAhead = busy
        }
      } else if (lines.nonEmpty && rng.nextInt(4) != 0) {
        val line = lines.head; lines = lines.tail
        for ((f, s) <- dut.io.feed.zipWithIndex) {
          val at = line * width + s
          f.valid.poke((at < table.length).B)
          if (at < table.length) table(at).zipWithIndex.foreach { case (b, c) => f.bits(c).poke(b.U) }
        }
      }
      dut.clock.step()
      if (begun && !busy) clearCycles += 1
      dut.io.begin.poke(false.B)
      dut.io.feed.foreach(_.valid.poke(false.B))
    }
  }

  /** As above. `fed`: the world's table was (or is now, if not begun) fed through `fed` before
    * start, and the third result is the cycles its counters' clear had before start; `ahead`:
    * the next world's table, fed while this one runs (and finished after it, if need be; the
    * next world's run then has it as `fed`). */
  def run(dut: BroadPhase, table: IndexedSeq[Seq[BigInt]], ready: () => Boolean, maxCycles: Long,
          fed: Option[Feeder] = None, ahead: Option[Feeder] = None)
         (stuck: Seq[(Int, Int)] => Nothing): (Seq[(Int, Int)], Long, Long) = {
    dut.io.begin.poke(false.B)
    dut.io.feed.foreach(_.valid.poke(false.B))
    fed.foreach { f => while (!f.done) f.step() }
    val feedCycles = fed.map(_.clearCycles).getOrElse(0L)
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
      ahead match {
        case Some(f) => f.step() // the feed's inputs this cycle, and the clock
        case None => dut.clock.step()
      }
      cycles += 1
      for ((addr, port) <- addrs.zip(dut.io.sphere)) {
        val data = if (addr < table.length) table(addr) else Seq.fill(4)(BigInt(0))
        data.zipWithIndex.foreach { case (b, f) => port.data(f).poke(b.U) }
      }
      if (cycles > maxCycles) stuck(pairs.toSeq)
    }
    (pairs.toSeq, cycles, feedCycles)
  }
}
