package collide.world

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.scpu.ScpuConfig
import collide.testutil.Seeds
import collide.world.model.{BroadPhaseModel, SphereClass}

class ChunkMatcherSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "ChunkMatcher"
  // The two cases with the longest runs take Verilator (seconds to build); treadle took
  // over 20 s for each. The others are quicker on treadle than a Verilator build.
  private val verilator = Seq(chiseltest.simulator.VerilatorBackendAnnotation)

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

  /** The pairs the model makes of a chunk's members and the probes streamed past it. */
  private def expected(members: Seq[(K, Int)], entries: Seq[P], slack: Int): Seq[(Int, Int)] =
    for (p <- entries; e = p.k; (m, pl) <- members
         if (if (p.anyCell) !p.own || e.index > m.index else e.cell == p.visit && owns(pl, p.off, m.index, e.index)) &&
            model.boxPass(tuple(m), tuple(e), BigInt(slack)))
      yield (math.min(m.index, e.index), math.max(m.index, e.index))

  /** One chunk: loads the members (the clear a cycle before the first load, or with it, as the
    * generator does), streams the probes past them with the input offered and the output ready
    * at random, and returns the pairs in the order they left. */
  private def runChunk(dut: ChunkMatcher, rng: scala.util.Random, members: Seq[(K, Int)], entries: Seq[P], slack: Int): Seq[(Int, Int)] = {
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
      assert(cycles < 10000, "stuck")
    }
    dut.io.in.valid.poke(false.B)
    got.toSeq
  }

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
        val want = expected(members, entries, slack)
        assert(runChunk(dut, rng, members, entries, slack) == want, s"round $round (slack=$slack, ${members.length} members, ${entries.length} entries)")
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

  /** A grid chunk at the near filter's limits, as the broad phase makes them: a coarse chunk's
    * members in its 8 cells (their q at the cells' edges, radii 0 to half a cell), probes in the
    * visits' cells (-1..2 from the base) or in the chunk's own coarse cell (pairs in the scan,
    * any cell), now and then one outside its visit's cell (far off); an edge of E = 256 or 192
    * filter units (2^F with F = 8, or 1.5 * 2^(F-1)), the slack 0 to its largest, 1 + 2^(F-5). */
  private def nearChunk(rng: scala.util.Random, first: Int): (Seq[(K, Int)], Seq[P], Int) = {
    val e = if (rng.nextBoolean()) 256 else 192
    val base = Seq.fill(3)(2 * (rng.nextInt(5) - 2))
    def at(cell: Seq[Int]) = cell.map(c => c * e + Seq(0, 1, e - 1, e - 2, rng.nextInt(e))(rng.nextInt(5)))
    def radius() = Seq(0, e / 2, e / 2 - 1, rng.nextInt(e / 2 + 1))(rng.nextInt(4))
    val members = (0 until 1 + rng.nextInt(chunk)).map { n =>
      val pl = rng.nextInt(8); val cell = base.zip(Seq(pl >> 2 & 1, pl >> 1 & 1, pl & 1)).map { case (b, o) => b + o }
      (K(first + n, cell, at(cell), radius()), pl)
    }
    val probes = (0 until rng.nextInt(40)).map { n =>
      val index = first + chunk + n
      if (rng.nextInt(4) == 0) { // a pair in the scan: a sphere of the same coarse cell
        val cell = base.map(_ + rng.nextInt(2))
        P(K(index, cell, at(cell), radius()), cell, Seq(0, 0, 0), anyCell = true, own = false)
      } else {
        val o = BroadPhaseModel.CoarseVisits(rng.nextInt(43)); val off = Seq(o._1, o._2, o._3)
        val visit = base.zip(off).map { case (b, d) => b + d }
        val cell = if (rng.nextInt(10) == 0) Seq.fill(3)(rng.nextInt(200) - 100) else visit
        P(K(index, cell, at(cell), radius()), visit, off, anyCell = false, own = false)
      }
    }
    (members, probes, Seq(0, 1, 9, rng.nextInt(10))(rng.nextInt(4)))
  }

  /** Rounds of nearChunk on a matcher with `near` bits and two wide slots; the rounds that
    * came out as the model says, and all of them. */
  private def nearRounds(name: String, near: Int): (Int, Int, Int) = {
    val rng = Seeds.rng(name)
    var same = 0; var rounds = 0; var pairs = 0
    test(new ChunkMatcher(itemW, cellBits, qWidth, chunk, hitQueue = 2, nearBits = near, wide = 2)).withAnnotations(verilator) { dut =>
      dut.clock.setTimeout(0)
      for (_ <- 0 until Seeds.cases(60)) {
        val (members, probes, slack) = nearChunk(rng, 16 * rng.nextInt(50))
        val want = expected(members, probes, slack)
        if (runChunk(dut, rng, members, probes, slack) == want) same += 1
        rounds += 1; pairs += want.length
      }
    }
    (same, rounds, pairs)
  }

  it should "give the model's pairs with near slots, for grid chunks at the edges of their cells, radii and slack" in {
    val near = ChunkMatcher.nearBits(8)
    val (same, rounds, pairs) = nearRounds("ChunkMatcherSpec-near", near)
    println(s"[ChunkMatcherSpec] near filter of $near bits: $rounds grid chunks, $pairs pairs, as the model says in $same")
    assert(same == rounds, s"${rounds - same} of $rounds chunks differ from the model")
    assert(pairs > 200, "the rounds should produce pairs")
    // Two bits fewer wrap differences of two cells: these chunks do reach the width.
    val (sameShort, roundsShort, _) = nearRounds("ChunkMatcherSpec-near-short", near - 2)
    assert(sameShort < roundsShort, s"$near - 2 near bits gave the model's pairs in every chunk: the cases do not reach the width")
  }

  it should "meet a large pass's probes anywhere with its wide slots, near slots built" in {
    // The large pass loads at most `wide` members: any q and radius (saturated too).
    val rng = Seeds.rng("ChunkMatcherSpec-near-large")
    test(new ChunkMatcher(itemW, cellBits, qWidth, chunk, nearBits = ChunkMatcher.nearBits(8), wide = 2)) { dut =>
      dut.clock.setTimeout(0)
      var pairs = 0
      for (r <- 0 until Seeds.cases(30)) {
        def far(i: Int) = K(i, Seq(0, 0, 0), Seq.fill(3)(rng.nextInt(1 << (qWidth - 1)) - (1 << (qWidth - 2))),
          Seq((1 << qWidth) - 1, rng.nextInt(1 << 14), rng.nextInt(256))(rng.nextInt(3)))
        val members = (0 until 1 + rng.nextInt(2)).map(i => (far(i), 0))
        val probes = (0 until rng.nextInt(30)).map(n => P(far(10 + n), Seq(0, 0, 0), Seq(0, 0, 0), anyCell = true, own = rng.nextBoolean()))
        val slack = rng.nextInt(10)
        val want = expected(members, probes, slack)
        assert(runChunk(dut, rng, members, probes, slack) == want, s"round $r")
        pairs += want.length
      }
      println(s"[ChunkMatcherSpec] large pass with near slots built: $pairs pairs")
      assert(pairs > 20, "the rounds should produce pairs")
    }
  }

  it should "pass the box filter exactly where the model does at the extremes of q, r and the slack" in {
    // A 4-bit fixed point: q from -8 to 7, r and slack up to 15, so every sum and difference
    // the filter forms is at the edge of its width. Probes take any cell (the cell rules out).
    val qw = 4
    val qs = Seq(-8, -7, -1, 0, 1, 6, 7); val rs = Seq(0, 1, 7, 8, 14, 15)
    def at(ax: Int, v: Int) = Seq.tabulate(3)(a => if (a == ax) v else 0)
    val keys = for ((q, n) <- (for (q <- qs; r <- rs) yield (q, r)).zipWithIndex) yield (n, q)
    val members = keys.map { case (n, (q, r)) => K(n, Seq(0, 0, 0), at(n % 3, q), r) }
    val probes = keys.map { case (n, (q, r)) => K(100 + n, Seq(0, 0, 0), at((n / 3) % 3, q), r) }
    val rng = Seeds.rng("ChunkMatcherSpec-extremes") // the back-pressure only
    val entries = probes.map(P(_, Seq(0, 0, 0), Seq(0, 0, 0), anyCell = true, own = false))
    test(new ChunkMatcher(itemW, cellBits, qw, chunk)).withAnnotations(verilator) { dut =>
      dut.clock.setTimeout(0)
      var pairs = 0; var misses = 0
      for (slack <- Seq(0, 1, 15); group <- members.grouped(chunk)) {
        val want = expected(group.map((_, 0)), entries, slack)
        assert(runChunk(dut, rng, group.map((_, 0)), entries, slack) == want, s"slack $slack, members ${group.map(m => (m.q, m.qr))}")
        pairs += want.length; misses += group.length * probes.length - want.length
      }
      println(s"[ChunkMatcherSpec] extremes: $pairs pairs passed and $misses refused, as the model says")
      assert(pairs > 1000 && misses > 300, "the extremes should both pass and fail the filter")
    }
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
