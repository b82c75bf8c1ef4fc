package collide.world

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.scpu.ScpuConfig
import collide.testutil.Seeds
import collide.world.model.{BroadPhaseModel, SphereClass}

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
  /** A member's place in a coarse chunk: half the time 0 (a chunk of one cell), else any of 8. */
  private def place(rng: scala.util.Random): Int = if (rng.nextBoolean()) 0 else rng.nextInt(8)
  /** A visit's offset from the chunk's base: a fine visit (own or half shell) or any coarse one. */
  private def offset(rng: scala.util.Random): Seq[Int] =
    if (rng.nextBoolean()) { val o = BroadPhaseModel.Visits(rng.nextInt(14)); Seq(o._1, o._2, o._3) }
    else { val o = BroadPhaseModel.CoarseVisits(rng.nextInt(43)); Seq(o._1, o._2, o._3) }
  /** The model's half-shell rule, for cells given as offsets from the chunk's base. */
  private def owns(place: Int, off: Seq[Int], i: Int, j: Int): Boolean =
    BroadPhaseModel.owns(SphereClass.Small(place >> 2 & 1, place >> 1 & 1, place & 1), SphereClass.Small(off(0), off(1), off(2)), i, j)

  private def poke(b: WorldKey, k: K): Unit = {
    b.index.poke(k.index.U); k.cell.zipWithIndex.foreach { case (c, i) => b.cell(i).poke(c.S) }
    k.q.zipWithIndex.foreach { case (q, i) => b.q(i).poke(q.S) }; b.qr.poke(k.qr.U)
  }

  private def pokeMember(b: ChunkMember, m: (K, Int)): Unit = { poke(b.key, m._1); b.place.poke(m._2.U) }

  private def pokeProbe(b: WorldProbe, p: P): Unit = {
    poke(b.key, p.k); p.visit.zipWithIndex.foreach { case (c, i) => b.cell(i).poke(c.S) }
    p.off.zipWithIndex.foreach { case (o, i) => b.off(i).poke(o.S) }
    b.anyCell.poke(p.anyCell.B); b.own.poke(p.own.B)
  }

  private def tuple(k: K) = (BigInt(k.q(0)), BigInt(k.q(1)), BigInt(k.q(2)), BigInt(k.qr))

  for (hq <- Seq(0, 1, 4)) it should s"emit every member-entry pair in each probe's visited cell that the member owns and the box filter passes, once, in order, under back-pressure (hit queue $hq)" in {
    val rng = Seeds.rng(if (hq == 0) "ChunkMatcherSpec" else s"ChunkMatcherSpec-h$hq")
    test(new ChunkMatcher(itemW, cellBits, qWidth, chunk, hq)) { dut =>
      dut.clock.setTimeout(0)
      var total = 0
      for (round <- 0 until Seeds.cases(40)) {
        val indices = rng.shuffle((0 until 1 << itemW).toList).take(chunk + 30)
        val members = indices.take(1 + rng.nextInt(chunk)).map(i => (key(rng, i), place(rng)))
        // Visits change from probe to probe (back to back in the generator); a member itself
        // comes by on own visits.
        val entries = (indices.drop(chunk).take(rng.nextInt(30)).map(key(rng, _)) ++ members.take(rng.nextInt(2)).map(_._1))
          .map(k => P(k, Seq(rng.nextInt(2), 3, -2), offset(rng), rng.nextInt(8) == 0, rng.nextBoolean()))
        val slack = rng.nextInt(4)
        val want = for (p <- entries; e = p.k; (m, pl) <- members
                        if (if (p.anyCell) !p.own || e.index > m.index else e.cell == p.visit && owns(pl, p.off, m.index, e.index)) &&
                           model.boxPass(tuple(m), tuple(e), BigInt(slack)))
          yield (math.min(m.index, e.index), math.max(m.index, e.index))
        // The clear comes a cycle before the first load, or with it (as the generator does).
        val clearWithLoad = rng.nextBoolean()
        if (!clearWithLoad) { dut.io.clear.poke(true.B); dut.clock.step(); dut.io.clear.poke(false.B) }
        for ((m, n) <- members.zipWithIndex) {
          dut.io.clear.poke((clearWithLoad && n == 0).B)
          dut.io.load.valid.poke(true.B); pokeMember(dut.io.load.bits, m); dut.clock.step()
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
      println(s"[ChunkMatcherSpec] hit queue $hq: $total pairs compared")
      assert(total > 50, "the rounds should produce pairs")
    }
  }

  for (hq <- Seq(0, 1, 4)) it should s"load the next chunk while the last chunk's hits leave, and lose none of them (drain behind, hit queue $hq)" in {
    val rng = Seeds.rng(s"ChunkMatcherSpec-drain-h$hq")
    test(new ChunkMatcher(itemW, cellBits, qWidth, chunk, hq, drainBehind = true)) { dut =>
      dut.clock.setTimeout(0)
      val want = scala.collection.mutable.ArrayBuffer.empty[(Int, Int)]
      val got = scala.collection.mutable.ArrayBuffer.empty[(Int, Int)]
      var cycles = 0
      var behind = 0 // clears while the last chunk still owed hits: what drainBehind is for
      // The output mostly stalled, so that hits pile up behind the chunks; its ready is set
      // for the next cycle before anything there is peeked (without a queue, in.ready follows it).
      def ready(): Unit = dut.io.out.ready.poke((rng.nextInt(3) == 0).B)
      def step(): Unit = {
        if (dut.io.out.valid.peek().litToBoolean && dut.io.out.ready.peek().litToBoolean)
          got += ((dut.io.out.bits.i.peek().litValue.toInt, dut.io.out.bits.j.peek().litValue.toInt))
        dut.clock.step(); cycles += 1; ready()
        assert(cycles < 100000, "stuck")
      }
      ready()
      for (round <- 0 until Seeds.cases(80)) {
        val indices = rng.shuffle((0 until 1 << itemW).toList).take(chunk + 30)
        val members = indices.take(1 + rng.nextInt(chunk)).map(i => (key(rng, i), place(rng)))
        // A third of the chunks see none to two spheres: the next clear then comes while the
        // chunk before the last still owes hits, which canClear must hold back.
        val entries = indices.drop(chunk).take(if (rng.nextInt(3) == 0) rng.nextInt(3) else rng.nextInt(30)).map(key(rng, _))
          .map(k => P(k, Seq(rng.nextInt(2), 3, -2), offset(rng), anyCell = false, own = false))
        val slack = rng.nextInt(4)
        want ++= (for (p <- entries; e = p.k; (m, pl) <- members
                       if e.cell == p.visit && owns(pl, p.off, m.index, e.index) && model.boxPass(tuple(m), tuple(e), BigInt(slack)))
          yield (math.min(m.index, e.index), math.max(m.index, e.index)))
        // The next chunk clears as soon as it may, as the generator does: its first load waits for canClear.
        while (!dut.io.canClear.peek().litToBoolean) step()
        if (!dut.io.idle.peek().litToBoolean) behind += 1
        for ((m, n) <- members.zipWithIndex) {
          dut.io.clear.poke((n == 0).B)
          dut.io.load.valid.poke(true.B); pokeMember(dut.io.load.bits, m); step()
        }
        dut.io.clear.poke(false.B); dut.io.load.valid.poke(false.B)
        dut.io.slack.poke(slack.U)
        var pendingIn = entries
        while (pendingIn.nonEmpty) {
          val offer = rng.nextInt(4) != 0
          dut.io.in.valid.poke(offer.B)
          if (offer) pokeProbe(dut.io.in.bits, pendingIn.head)
          if (offer && dut.io.in.ready.peek().litToBoolean) pendingIn = pendingIn.tail
          step()
        }
        dut.io.in.valid.poke(false.B)
      }
      while (!dut.io.idle.peek().litToBoolean) step()
      assert(got.toSeq == want.toSeq, s"${got.length} pairs against ${want.length}")
      println(s"[ChunkMatcherSpec] drain behind, hit queue $hq: ${want.length} pairs compared, $behind chunks loaded while hits were owed")
      assert(want.length > 50, "the rounds should produce pairs")
      assert(behind > 5, s"only $behind chunks were loaded while the last one's hits were owed: the case tests nothing")
    }
  }

  /** Cycles to accept `entries` probes, of which the first hits every member and the rest
    * none, with the output always ready; and the pairs that came out. */
  private def burst(hq: Int, entries: Int): (Int, Int) = {
    var result = (0, 0)
    test(new ChunkMatcher(itemW, cellBits, qWidth, chunk, hq)) { dut =>
      val members = (0 until chunk).map(i => K(i, Seq(0, 3, -2), Seq(0, 768, -512), 10))
      for ((m, n) <- members.zipWithIndex) {
        dut.io.clear.poke((n == 0).B); dut.io.load.valid.poke(true.B); pokeMember(dut.io.load.bits, (m, 0)); dut.clock.step()
      }
      dut.io.clear.poke(false.B); dut.io.load.valid.poke(false.B); dut.io.slack.poke(0.U); dut.io.out.ready.poke(true.B)
      // Probe 0 sits on the members (a later index, own cell: every member takes it); the others are far off.
      val probes = (0 until entries).map(n => P(K(100 + n, Seq(0, 3, -2), Seq(if (n == 0) 0 else 200 + 100 * n, 768, -512), 10),
        Seq(0, 3, -2), Seq(0, 0, 0), anyCell = false, own = false))
      var left = probes; var cycles = 0; var pairs = 0
      while (left.nonEmpty || !dut.io.idle.peek().litToBoolean) {
        dut.io.in.valid.poke(left.nonEmpty.B)
        if (left.nonEmpty) pokeProbe(dut.io.in.bits, left.head)
        if (dut.io.out.valid.peek().litToBoolean) pairs += 1
        if (left.nonEmpty && dut.io.in.ready.peek().litToBoolean) { left = left.tail; if (left.isEmpty) result = (cycles + 1, 0) }
        dut.clock.step(); cycles += 1
        assert(cycles < 1000, "stuck")
      }
      result = (result._1, pairs)
    }
    result
  }

  it should "keep taking streamed spheres while a burst of hits leaves, with a hit queue" in {
    val (stalled, pairsStalled) = burst(0, 6)
    val (queued, pairsQueued) = burst(2, 6)
    assert(pairsStalled == chunk && pairsQueued == chunk, s"every member's pair with the first probe: $pairsStalled, $pairsQueued")
    // Without a queue the stream waits for all but the last of the first sphere's hits.
    assert(stalled == 6 + chunk - 1, s"no queue: 6 probes accepted in $stalled cycles")
    assert(queued == 6, s"a queue of 2: 6 probes accepted in $queued cycles")
  }

  it should "refuse a member beyond the chunk and say so" in {
    test(new ChunkMatcher(itemW, cellBits, qWidth, chunk)) { dut =>
      val rng = new scala.util.Random(1)
      for (i <- 0 to chunk) { dut.io.load.valid.poke(true.B); pokeMember(dut.io.load.bits, (key(rng, i), 0)); dut.clock.step() }
      dut.io.load.valid.poke(false.B)
      assert(dut.io.overflow.peek().litToBoolean)
      dut.io.clear.poke(true.B); dut.clock.step()
      assert(!dut.io.overflow.peek().litToBoolean)
    }
  }
}

object ChunkMatcherSpec {
  final case class K(index: Int, cell: Seq[Int], q: Seq[Int], qr: Int)
  /** A streamed sphere and its visit: the cell it must be in and that cell's offset from the
    * chunk's base (unless anyCell), own (anyCell only). */
  final case class P(k: K, visit: Seq[Int], off: Seq[Int], anyCell: Boolean, own: Boolean)
}
