package collide.afu

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.scpu.ScpuConfig
import collide.scpu.model.ScpuModel
import collide.testutil.{Builds, Seeds, Slow}
import collide.world.BroadPhaseWorlds
import collide.world.model.{BroadPhaseModel, WorldSphere}

/** World mode end to end: the host sends only the sphere table, the AFU's broad phase finds
  * the candidates, its SCPUs compute them, and the records name both spheres. Every world is
  * checked against the all-pairs golden model (ScpuModel on every i < j), so a pair the
  * broad phase missed, doubled or invented shows, over hostile, HARP-like and ideal links
  * (random latency, reordering, back-pressure). Pair mode runs on the same AFU in between. */
class AfuWorldSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "Afu in world mode"

  // Cases of one configuration share its Verilator build (Builds).
  private def annos(cfg: AfuConfig) = Builds.verilator("AfuWorldSpec", cfg.id)
  private val behaviours = Seq(LinkBehaviour.hostile, LinkBehaviour.harp, LinkBehaviour.ideal)

  /** The records world mode must write: every i < j of finite spheres that ScpuModel calls
    * a hit, by pair field (i | j << 12). Non-finite spheres are paired with nothing. */
  def expected(cfg: AfuConfig, world: IndexedSeq[WorldSphere]): Map[Int, AfuRecord] = {
    val m = ScpuModel(cfg.scpu)
    val lp = cfg.scpu.linkParams
    def finite(v: BigInt) = ((v >> (lp.format.sigBits - 1)) & ((BigInt(1) << lp.format.expBits) - 1)) != (BigInt(1) << lp.format.expBits) - 1
    val ok = world.map(s => Seq(s.x, s.y, s.z, s.r).forall(finite))
    (for {
      j <- world.indices; i <- 0 until j if ok(i) && ok(j)
      a = world(i); b = world(j)
      res = m.collide(a.x, a.y, a.z, a.r, b.x, b.y, b.z, b.r, BigInt(0)) if res.hit
    } yield {
      val pair = i | (j << RecordTag.WORLD_INDEX_BITS)
      pair -> AfuWorlds.record(cfg.layout, res, pair)
    }).toMap
  }

  /** One world-mode run; returns failures (empty: every contact exactly once, bit for bit). */
  def runWorld(dut: Afu, cfg: AfuConfig, world: IndexedSeq[WorldSphere], beh: LinkBehaviour, seed: Long,
               capacity: Option[Long] = None): (Seq[String], Status) = {
    val lay = cfg.layout
    val want = expected(cfg, world)
    val model = new BroadPhaseModel(cfg.scpu, cfg.broadPhase.get).run(world)
    val cap = capacity.getOrElse(want.size.toLong + 3)
    val w = World(lay, world.map(s => Seq(s.x, s.y, s.z, s.r)), IndexedSeq.empty, dense = false, capacity = Some(cap))
    val mem = new HostMemoryModel(dut.io, dut.clock, beh, seed, cfg.maxReadsOutstanding, cfg.maxWritesOutstanding)
    val n = world.length.toLong
    val r = AfuRun.run(mem, w, maxCycles = 200000L + 60L * n * n,
      csrOverride = Map(Csr.MODE -> Csr.MODE_WORLD, Csr.NUM_PAIRS -> 12345, Csr.PAIR_BASE -> 0)) // both ignored
    check(cfg, world, cap, r)
  }

  /** A world run's result against the all-pairs golden model (failures, and its status line). */
  def check(cfg: AfuConfig, world: IndexedSeq[WorldSphere], cap: Long, r: RunResult): (Seq[String], Status) = {
    val lay = cfg.layout
    val want = expected(cfg, world)
    val model = new BroadPhaseModel(cfg.scpu, cfg.broadPhase.get).run(world)
    val errs = scala.collection.mutable.ArrayBuffer[String]()
    val st = r.status.getOrElse(return (Seq(s"no status line in ${r.cycles} cycles"), Status(IndexedSeq.fill(16)(0L))))
    val written = math.min(want.size.toLong, cap)
    val expErr = if (want.size > cap) ErrorFlags.CAPACITY else 0
    if (st.errors != expErr) errs += s"error flags 0x${st.errors.toHexString}, expected 0x${expErr.toHexString}"
    if (st.processed != model.candidates.length) errs += s"pairs processed ${st.processed}, the model has ${model.candidates.length} candidates"
    if (st.found != want.size) errs += s"contacts found ${st.found}, expected ${want.size}"
    if (st.written != written) errs += s"records written ${st.written}, expected $written"
    val words = st.words
    if (words(StatusLine.WORLD_CELL_LEVEL / 4).toInt != model.level) errs += s"cell level ${words(StatusLine.WORLD_CELL_LEVEL / 4).toInt}, model ${model.level}"
    if (words(StatusLine.WORLD_LARGE / 4) != model.stats.large) errs += s"large spheres ${words(StatusLine.WORLD_LARGE / 4)}, model ${model.stats.large}"
    if (words(StatusLine.CYCLES_BROAD / 4) == 0) errs += "no broad-phase cycles counted"
    if (r.writes.last.addr != r.statusAddr) errs += "the status line is not the last write"
    val lines = r.writes.filter(_.addr != r.statusAddr).map(e => (e.addr - r.contactBase).toLong -> e.data)
    if (lines.map(_._1).distinct.size != lines.size) errs += "a contact line written twice"
    if (lines.size != lay.contactLines(written)) errs += s"${lines.size} contact lines, expected ${lay.contactLines(written)}"
    val byLine = lines.toMap
    val R = lay.recordsPerLine
    val recs = (0L until written).map(rn => AfuRecord.decode(byLine.getOrElse(rn / R, BigInt(0)), (rn % R).toInt, lay))
    val pairs = recs.map(_.pair)
    if (pairs.distinct.size != pairs.size) errs += "a pair has two records"
    for (rec <- recs if !want.get(rec.pair).contains(rec); if errs.size < 20) {
      val (i, j) = (rec.pair & 0xfff, rec.pair >> RecordTag.WORLD_INDEX_BITS)
      errs += s"record for ($i, $j): $rec, expected ${want.get(rec.pair).map(_.toString).getOrElse("no contact")}"
    }
    if (written == want.size && pairs.toSet != want.keySet) {
      val missing = (want.keySet -- pairs).take(5).map(p => (p & 0xfff, p >> 12))
      errs += s"${(want.keySet -- pairs).size} contacts missing, e.g. ${missing.mkString(" ")}"
    }
    (errs.toSeq, st)
  }

  /** One run of a queue: a world (world mode) or a pair world (pair mode); `late`: started only
    * once the run before it is over, so that its table is not loaded ahead. */
  final case class Queued(world: Either[IndexedSeq[WorldSphere], World], late: Boolean = false, tooMany: Boolean = false)

  /** Runs started back to back through the run queue: each run has its own table, pair list,
    * contact buffer and status line; run k is started once run k - 2's status line is in host
    * memory (the queue holds one run), a late run once run k - 1's is. Returns each run's
    * result (its writes: those to its buffers). */
  def runQueue(dut: Afu, cfg: AfuConfig, runs: Seq[Queued], beh: LinkBehaviour, seed: Long): Seq[RunResult] = {
    val lay = cfg.layout
    val mem = new HostMemoryModel(dut.io, dut.clock, beh, seed, cfg.maxReadsOutstanding, cfg.maxWritesOutstanding)
    def sphereBase(k: Int) = BigInt(0x100000 + k * 0x2000); def pairBase(k: Int) = BigInt(0x400000 + k * 0x4000)
    def contactBase(k: Int) = BigInt(0x800000 + k * 0x20000); def statusAddr(k: Int) = BigInt(0xf00000 + k)
    def spheres(q: Queued): IndexedSeq[Seq[BigInt]] = q.world.fold(_.map(s => Seq(s.x, s.y, s.z, s.r)), _.spheres)
    def capacity(q: Queued): Long = q.world.fold(ws => expected(cfg, ws).size.toLong + 3, pw => pw.capacity.getOrElse(lay.compactSlotsFor(pw.pairs.size.toLong) + 3))
    for ((q, k) <- runs.zipWithIndex)
      AfuRun.writeLines(mem, lay, spheres(q), q.world.fold(_ => Nil, _.pairs), sphereBase(k), pairBase(k))
    def start(k: Int): Unit = {
      val q = runs(k)
      val n = if (q.tooMany) cfg.maxSpheres + 1L else spheres(q).size.toLong
      val csrs = Seq(Csr.SPHERE_BASE -> sphereBase(k), Csr.NUM_SPHERES -> BigInt(n),
        Csr.PAIR_BASE -> pairBase(k), Csr.NUM_PAIRS -> BigInt(q.world.fold(_ => 0, _.pairs.size)),
        Csr.CONTACT_BASE -> contactBase(k), Csr.CONTACT_CAPACITY -> BigInt(capacity(q)), Csr.STATUS_ADDR -> statusAddr(k),
        Csr.MODE -> BigInt(q.world.fold(_ => Csr.MODE_WORLD, pw => if (pw.dense) Csr.MODE_DENSE else 0)))
      for ((i, v) <- csrs) mem.writeCsr(i, v)
      mem.writeCsr(Csr.CTRL, Csr.CTRL_START)
    }
    val t0 = mem.cycle
    var started = 0
    val limit = 400000L + runs.map(q => 60L * spheres(q).size * spheres(q).size + 400L * q.world.fold(_ => 0, _.pairs.size)).sum
    def done(k: Int) = k < 0 || mem.committed.contains(statusAddr(k))
    while (!(done(runs.size - 1) && mem.idleLink()) && mem.cycle - t0 < limit) {
      if (started < runs.size && done(started - (if (runs(started).late) 1 else 2))) { start(started); started += 1 }
      else mem.step()
    }
    runs.indices.map { k =>
      val mine = mem.writes.filter(e => e.addr == statusAddr(k) || (e.addr >= contactBase(k) && e.addr < contactBase(k) + 0x20000)).toSeq
      RunResult(mine.find(_.addr == statusAddr(k)).map(e => Status(e.data)), mine, mem.cycle - t0, contactBase(k), statusAddr(k))
    }
  }

  /** A queue of runs through `runQueue`, each checked like a run of its own. Returns the status lines. */
  def checkQueue(dut: Afu, cfg: AfuConfig, runs: Seq[(String, Queued)], beh: LinkBehaviour, seed: Long): Seq[Status] = {
    val results = runQueue(dut, cfg, runs.map(_._2), beh, seed)
    for (((label, q), r) <- runs.zip(results)) yield {
      val errs = (q.world, q.tooMany) match {
        case (_, true) => r.status match {
          case Some(st) if st.errors == ErrorFlags.TOO_MANY_SPHERES && st.processed == 0 && r.writes.size == 1 => Nil
          case other => Seq(s"a refused run: $other, ${r.writes.size} writes")
        }
        case (Left(ws), _) => check(cfg, ws, expected(cfg, ws).size.toLong + 3, r)._1
        case (Right(pw), _) => AfuRun.check(pw, AfuWorlds.expect(cfg.scpu, pw), r)
      }
      assert(errs.isEmpty, s"${cfg.id}, queued run $label (${beh.name}, seed $seed): ${errs.mkString("; ")}\n${r.status}")
      r.status.get
    }
  }

  def worlds(rng: scala.util.Random, cfg: AfuConfig): Seq[(String, IndexedSeq[WorldSphere])] =
    BroadPhaseWorlds.hardCases(rng, onePointSpheres = 40).map { case (l, w) => l -> BroadPhaseWorlds.bits(cfg.scpu.linkFormat, w) }

  def endToEnd(cfg: AfuConfig, spec: String): Unit = {
    val rng = Seeds.rng(s"AfuWorldSpec-$spec")
    test(new Afu(cfg)).withAnnotations(annos(cfg)) { dut =>
      dut.clock.setTimeout(0)
      var contacts = 0L; var candidates = 0L
      for (((label, world), i) <- worlds(rng, cfg).zipWithIndex) {
        val beh = behaviours(i % behaviours.size)
        val (errs, st) = runWorld(dut, cfg, world, beh, rng.nextLong())
        assert(errs.isEmpty, s"${cfg.id}, $label (${world.length} spheres, ${beh.name}): ${errs.mkString("; ")}\n$st")
        contacts += st.found; candidates += st.processed
        // pair mode on the same AFU, between world runs
        if (i % 4 == 3) {
          val pw = AfuWorlds.random(rng, cfg, 1 + rng.nextInt(100), dense = i % 8 == 7, specials = true)
          val mem = new HostMemoryModel(dut.io, dut.clock, beh, rng.nextLong(), cfg.maxReadsOutstanding, cfg.maxWritesOutstanding)
          val r = AfuRun.run(mem, pw)
          val perrs = AfuRun.check(pw, AfuWorlds.expect(cfg.scpu, pw), r)
          assert(perrs.isEmpty, s"${cfg.id}: pair mode after $label: ${perrs.mkString("; ")}\n${r.status}")
        }
      }
      // With a run queue, the same worlds once more, started back to back (each table loaded
      // while the run before it computes, alternating the two tables).
      if (cfg.runQueue) checkQueue(dut, cfg, worlds(rng, cfg).map { case (l, w) => l -> Queued(Left(w)) }, LinkBehaviour.harp, rng.nextLong())
      println(s"[AfuWorldSpec] ${cfg.id}: ${worlds(new scala.util.Random(0), cfg).size} worlds, $candidates candidates, " +
        s"$contacts contacts, all equal to the all-pairs golden model" + (if (cfg.runQueue) ", alone and queued" else ""))
    }
  }

  private val small = AfuConfig.world.copy(scpus = 2, maxSpheres = 256, world = AfuConfig.world.world.map(_.copy(runQueue = false)))

  it should "find every contact of every hard case exactly once, bit for bit the all-pairs golden model (two fp32 SCPUs, derived records)" in {
    endToEnd(small, "fp32")
  }

  // A broad phase of four lanes (fed, four sort ports, the preset's grid) beside the banked
  // table: the 16-lane one is the case above's, and a second 16-lane build costs minutes of CI.
  // The banked AFU also has the run queue, so the queue's cases below share its build; it starts
  // a queued world's broad phase ahead (its pairs held until its run), queues eight candidate
  // lines, and clears the sort's counters behind each scatter (docs/afu.md, "Starting ahead").
  private val banked = small.copy(scpus = 4, ramPorts = SphereRamPorts.Banked(Some(4)),
    world = small.world.map(w => WorldConfig(w.broadPhase.copy(lanes = 4, sortPorts = 4, clearBehind = true), runQueue = true, lineQueue = 8, startAhead = true)))

  it should "find the same contacts, and the pair mode's, with the sphere table in four banks (four fp32 SCPUs, eight reads a cycle), alone and through the run queue" in {
    endToEnd(banked, "fp32-banked")
  }

  it should "find the same contacts with three broad-phase lanes (four fp32 SCPUs; one sphere copy shared by two lanes, one for the third)" in {
    endToEnd(small.copy(scpus = 4, world = Some(WorldConfig(collide.world.BroadPhaseParams.default.copy(lanes = 3)))), "fp32-lanes")
  }

  it should "stop at the contact buffer's capacity, refuse dense world runs, and hold maxSpheres spheres" in {
    val rng = Seeds.rng("AfuWorldSpec-edges")
    test(new Afu(small)).withAnnotations(annos(small)) { dut =>
      dut.clock.setTimeout(0)
      val cloud = BroadPhaseWorlds.bits(small.scpu.linkFormat, BroadPhaseWorlds.uniform(rng, 120, contacts = 4))
      for (cap <- Seq(0L, 1L, 7L)) {
        val (errs, st) = runWorld(dut, small, cloud, LinkBehaviour.hostile, rng.nextLong(), capacity = Some(cap))
        assert(errs.isEmpty, s"capacity $cap: ${errs.mkString("; ")}\n$st")
        assert((st.errors & ErrorFlags.CAPACITY) != 0, s"capacity $cap: the buffer overflowed unflagged")
      }
      val w = World(small.layout, cloud.map(s => Seq(s.x, s.y, s.z, s.r)), IndexedSeq.empty, dense = true, capacity = Some(100))
      val mem = new HostMemoryModel(dut.io, dut.clock, LinkBehaviour.ideal, 1, small.maxReadsOutstanding, small.maxWritesOutstanding)
      val r = AfuRun.run(mem, w, csrOverride = Map(Csr.MODE -> (Csr.MODE_WORLD | Csr.MODE_DENSE)))
      assert(r.status.exists(_.errors == ErrorFlags.BAD_CONFIG) && r.writes.size == 1, s"dense world mode: ${r.status}")
      val full = BroadPhaseWorlds.bits(small.scpu.linkFormat, BroadPhaseWorlds.uniform(rng, small.maxSpheres))
      val (errs, st) = runWorld(dut, small, full, LinkBehaviour.harp, rng.nextLong())
      assert(errs.isEmpty, s"maxSpheres spheres: ${errs.mkString("; ")}\n$st")
    }
  }

  // The queue's cases run on the banked AFU above (its build is cached); the preset's replicated
  // tables are queued by the Slow preset case and by the host's tests (test/test_afu_world.cpp).
  private val queued = banked

  it should "find every contact of every hard case through the run queue, the next table loading while a run computes, with queued pair-mode and refused runs among them" in {
    val rng = Seeds.rng("AfuWorldSpec-queue")
    test(new Afu(queued)).withAnnotations(annos(queued)) { dut =>
      dut.clock.setTimeout(0)
      val ws = worlds(rng, queued)
      for ((beh, b) <- behaviours.zipWithIndex) {
        // every hard case once per link, started back to back; some late (loaded after the run
        // before, not ahead), a pair-mode run and a refused one among them
        val runs = ws.zipWithIndex.map { case ((label, w), i) => label -> Queued(Left(w), late = (i + b) % 5 == 4) } ++
          Seq("pairs" -> Queued(Right(AfuWorlds.random(rng, queued, 1 + rng.nextInt(100), dense = b == 1, specials = true))),
            "refused" -> Queued(Left(ws.head._2), tooMany = true), "after" -> Queued(Left(ws.last._2)))
        val order = rng.shuffle(runs.init) :+ runs.last
        checkQueue(dut, queued, order, beh, rng.nextLong())
      }
      println(s"[AfuWorldSpec] ${queued.id}: ${ws.size} worlds queued on each of ${behaviours.size} links, equal to the all-pairs golden model")
    }
  }

  it should "load each queued world's table while the run before it computes, fed to its broad phase as it arrives (no load cycles after the first run; started ahead of its run, never late), also where a run is too short to hide the next read" in {
    val rng = Seeds.rng("AfuWorldSpec-prefetch")
    test(new Afu(queued)).withAnnotations(annos(queued)) { dut =>
      dut.clock.setTimeout(0)
      val clouds = Seq.fill(5)(BroadPhaseWorlds.bits(queued.scpu.linkFormat, BroadPhaseWorlds.uniform(rng, 200, contacts = 2)))
      val st = checkQueue(dut, queued, clouds.zipWithIndex.map { case (c, i) => s"cloud $i" -> Queued(Left(c)) }, LinkBehaviour.harp, rng.nextLong())
      assert(st.head.cycLoad > 0, s"the first run's table is read in its own time: ${st.head}")
      for ((s, i) <- st.zipWithIndex.tail) assert(s.cycLoad == 0, s"run $i waited ${s.cycLoad} cycles for its table: $s")
      // Started late, the same runs each wait for their table.
      val late = checkQueue(dut, queued, clouds.zipWithIndex.map { case (c, i) => s"late cloud $i" -> Queued(Left(c), late = true) }, LinkBehaviour.harp, rng.nextLong())
      for ((s, i) <- late.zipWithIndex) assert(s.cycLoad > 0, s"late run $i: no load cycles: $s")
      // A queued table is fed to the broad phase as it arrives, as a late run's is, so its
      // broad phase does not read it again (that would take 200 / 4 cycles more a run).
      def broad(s: Status) = s.words(StatusLine.CYCLES_BROAD / 4)
      println(s"[AfuWorldSpec] broad-phase cycles queued ${st.map(broad).mkString(" ")}, late ${late.map(broad).mkString(" ")}")
      def total(s: Status) = s.words(StatusLine.CYCLES_TOTAL / 4)
      if (!queued.world.exists(_.startAhead))
        for (((q, l), i) <- st.zip(late).zipWithIndex)
          assert(broad(q) <= broad(l) + 8, s"run $i's broad phase took ${broad(q)} cycles queued, ${broad(l)} started late")
      else {
        // Started ahead, a queued run's broad phase begins while the run before drains: before
        // its own run's check, so it can count more cycles than its run. A late run's never does.
        println(s"[AfuWorldSpec] run cycles queued ${st.map(total).mkString(" ")}, late ${late.map(total).mkString(" ")}")
        assert(st.tail.exists(s => broad(s) > total(s)), s"no queued run's broad phase started ahead of its run: ${st.map(s => broad(s) -> total(s))}")
        for ((s, i) <- late.zipWithIndex) assert(broad(s) < total(s), s"late run $i: its broad phase began before its run: $s")
      }
      // Runs too short to hide the next table's read: it is still arriving when its run becomes
      // current, and every line of it must still reach the broad phase.
      val tiny = IndexedSeq(Seq.empty[BroadPhaseWorlds.S], BroadPhaseWorlds.uniform(rng, 1),
        BroadPhaseWorlds.uniform(rng, 7, contacts = 2)).map(w => BroadPhaseWorlds.bits(queued.scpu.linkFormat, w))
      checkQueue(dut, queued, (0 until 9).map(i => s"tiny $i" -> Queued(Left(tiny(i % 3)))), LinkBehaviour.harp, rng.nextLong())
    }
  }

  it should "match the golden model with four fp16 SCPUs on a binary16 link (full records)" taggedAs Slow in {
    endToEnd(AfuConfig.world.copy(scpus = 4, maxSpheres = 256, scpu = ScpuConfig.fp16, records = Some(RecordLayout.Full)), "fp16")
  }

  it should "match the golden model in the world preset (16 fp32 SCPUs, 4096 spheres)" taggedAs Slow in {
    endToEnd(AfuConfig.world, "preset")
  }

  it should "match the golden model in the world-fit preset (8 lanes, 4 fp32 SCPUs: the world preset on the paper's part), alone and queued" taggedAs Slow in {
    endToEnd(AfuConfig.worldFit, "world-fit")
  }

  it should "match the golden model in the world32 preset (32 lanes, 16 sort ports, queued runs started ahead, counters cleared behind), alone and queued" taggedAs Slow in {
    endToEnd(AfuConfig.world32, "world32")
  }
}
