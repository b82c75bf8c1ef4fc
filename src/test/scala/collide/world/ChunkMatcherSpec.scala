package collide.world

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.scpu.ScpuConfig
import collide.testutil.Seeds
import collide.world.model.BroadPhaseModel

class ChunkMatcherSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "ChunkMatcher"

  private val itemW = 10; private val cellBits = 8; private val qWidth = 17; private val chunk = 8
  import ChunkMatcherSpec._

  private val model = new BroadPhaseModel(ScpuConfig.fp32)

  /** A sphere in one of two neighbouring cells, its fixed point near the others' so that the
    * box filter passes about half the time; qr sometimes saturated (a huge sphere). */
  private def key(rng: scala.util.Random, index: Int): K = {
    val cell = Seq(rng.nextInt(2), 3, -2)
    K(index, cell, cell.map(c => c * 256 + rng.nextInt(256)), if (rng.nextInt(10) == 0) (1 << qWidth) - 1 else rng.nextInt(80))
  }

  private def poke(b: WorldKey, k: K): Unit = {
    b.index.poke(k.index.U); k.cell.zipWithIndex.foreach { case (c, i) => b.cell(i).poke(c.S) }
    k.q.zipWithIndex.foreach { case (q, i) => b.q(i).poke(q.S) }; b.qr.poke(k.qr.U)
  }

  private def pokeProbe(b: WorldProbe, p: P): Unit = {
    poke(b.key, p.k); p.visit.zipWithIndex.foreach { case (c, i) => b.cell(i).poke(c.S) }
    b.anyCell.poke(p.anyCell.B); b.own.poke(p.own.B)
  }

  private def tuple(k: K) = (BigInt(k.q(0)), BigInt(k.q(1)), BigInt(k.q(2)), BigInt(k.qr))

  it should "emit every member-entry pair in each probe's visited cell that passes the box filter, once, in order, under back-pressure" in {
    val rng = Seeds.rng("ChunkMatcherSpec")
    test(new ChunkMatcher(itemW, cellBits, qWidth, chunk)) { dut =>
      dut.clock.setTimeout(0)
      var total = 0
      for (round <- 0 until Seeds.cases(40)) {
        val indices = rng.shuffle((0 until 1 << itemW).toList).take(chunk + 30)
        val members = indices.take(1 + rng.nextInt(chunk)).map(key(rng, _))
        // Visits change from probe to probe (back to back in the generator); a member itself
        // comes by on own visits.
        val entries = (indices.drop(chunk).take(rng.nextInt(30)).map(key(rng, _)) ++ members.take(rng.nextInt(2)))
          .map(k => P(k, Seq(rng.nextInt(2), 3, -2), rng.nextInt(8) == 0, rng.nextBoolean()))
        val slack = rng.nextInt(4)
        val want = for (p <- entries; e = p.k; m <- members
                        if (p.anyCell || e.cell == p.visit) && (!p.own || e.index > m.index) &&
                           model.boxPass(tuple(m), tuple(e), BigInt(slack)))
          yield (math.min(m.index, e.index), math.max(m.index, e.index))
        // The clear comes a cycle before the first load, or with it (as the generator does).
        val clearWithLoad = rng.nextBoolean()
        if (!clearWithLoad) { dut.io.clear.poke(true.B); dut.clock.step(); dut.io.clear.poke(false.B) }
        for ((m, n) <- members.zipWithIndex) {
          dut.io.clear.poke((clearWithLoad && n == 0).B)
          dut.io.load.valid.poke(true.B); poke(dut.io.load.bits, m); dut.clock.step()
        }
        dut.io.clear.poke(false.B)
        dut.io.load.valid.poke(false.B)
        dut.io.slack.poke(slack.U)
        val got = scala.collection.mutable.ArrayBuffer.empty[(Int, Int)]
        var pendingIn = entries
        var cycles = 0
        while (pendingIn.nonEmpty || !dut.io.idle.peek().litToBoolean) {
          val offer = pendingIn.nonEmpty && rng.nextInt(4) != 0
          dut.io.in.valid.poke(offer.B)
          if (offer) pokeProbe(dut.io.in.bits, pendingIn.head)
          dut.io.out.ready.poke((rng.nextInt(3) != 0).B)
          if (dut.io.out.valid.peek().litToBoolean && dut.io.out.ready.peek().litToBoolean)
            got += ((dut.io.out.bits.i.peek().litValue.toInt, dut.io.out.bits.j.peek().litValue.toInt))
          if (offer && dut.io.in.ready.peek().litToBoolean) pendingIn = pendingIn.tail
          dut.clock.step(); cycles += 1
          assert(cycles < 10000, s"round $round: stuck")
        }
        dut.io.in.valid.poke(false.B)
        assert(got.toSeq == want, s"round $round (slack=$slack, ${members.length} members, ${entries.length} entries)")
        assert(!dut.io.overflow.peek().litToBoolean)
        total += want.length
      }
      println(s"[ChunkMatcherSpec] $total pairs compared")
      assert(total > 50, "the rounds should produce pairs")
    }
  }

  it should "refuse a member beyond the chunk and say so" in {
    test(new ChunkMatcher(itemW, cellBits, qWidth, chunk)) { dut =>
      val rng = new scala.util.Random(1)
      for (i <- 0 to chunk) { dut.io.load.valid.poke(true.B); poke(dut.io.load.bits, key(rng, i)); dut.clock.step() }
      dut.io.load.valid.poke(false.B)
      assert(dut.io.overflow.peek().litToBoolean)
      dut.io.clear.poke(true.B); dut.clock.step()
      assert(!dut.io.overflow.peek().litToBoolean)
    }
  }
}

object ChunkMatcherSpec {
  final case class K(index: Int, cell: Seq[Int], q: Seq[Int], qr: Int)
  /** A streamed sphere and its visit: the cell it must be in (unless anyCell), own. */
  final case class P(k: K, visit: Seq[Int], anyCell: Boolean, own: Boolean)
}
