package collide.world

import chisel3._
import chiseltest._
import chiseltest.simulator.VerilatorBackendAnnotation
import chiseltest.internal.CachingAnnotation
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.FloatFormat
import collide.scpu.ScpuConfig
import collide.testutil.{Seeds, Slow}
import collide.world.BroadPhaseWorlds._
import collide.world.BroadPhaseDriver.Feeder
import collide.world.model._

/** The broad phase's RTL against its golden model, world by world: the same candidate
  * pairs (with one lane the grid's in the model's order and the large pass's as a set; with
  * several lanes all of them as a set, each pair once), the same k and classes, under random
  * back-pressure on every lane's pair stream. */
class BroadPhaseSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "BroadPhase"

  private val maxSpheres = 256
  // Treadle runs this design at a few hundred cycles a second; Verilator, built once per
  // configuration and cached while the design is unchanged, at tens of thousands.
  private val annos = Seq(VerilatorBackendAnnotation, CachingAnnotation)

  /** What the RTL did, and (once checked) the golden model's work counts for the same world. */
  case class Run(pairs: Seq[(Int, Int)], status: Map[String, BigInt], cycles: Long, modelStats: Option[BroadPhaseStats] = None)

  /** Serves the sphere table (one cycle of read latency) and takes the pairs, ready with
    * probability `readyOdds`. */
  private def run(dut: BroadPhase, table: IndexedSeq[Seq[BigInt]], rng: scala.util.Random, readyOdds: Double,
                  fed: Option[Feeder] = None, ahead: Option[Feeder] = None): Run = {
    val limit = 100000L + 40L * table.length * table.length
    val (pairs, cycles, feedCycles) =
      BroadPhaseDriver.run(dut, table, () => rng.nextDouble() < readyOdds, limit, fed, ahead) { got =>
      val s = dut.io.status
      fail(s"the broad phase never finished: ${table.length} spheres, cycles load ${s.cycLoad.peek().litValue} " +
        s"classify ${s.cycClassify.peek().litValue} prefix ${s.cycPrefix.peek().litValue} scatter ${s.cycScatter.peek().litValue} " +
        s"grid ${s.cycGrid.peek().litValue} large ${s.cycLarge.peek().litValue}, ${got.length} pairs out")
    }
    val s = dut.io.status
    val fields = Seq("excluded" -> s.excluded, "large" -> s.large, "small" -> s.small, "candidates" -> s.candidates,
      "cells" -> s.cells, "chunks" -> s.chunks, "cycTotal" -> s.cycTotal, "cycLoad" -> s.cycLoad, "cycPrefix" -> s.cycPrefix,
      "cycGrid" -> s.cycGrid, "cycLarge" -> s.cycLarge, "scanned" -> s.scanned, "probes" -> s.probes) ++
      GridCycle.names.zip(s.laneCycles).map { case (n, d) => s"lane_$n" -> d }
    val fieldValues = fields.map { case (n, d) => n -> d.peek().litValue }.toMap + ("feedCycles" -> BigInt(feedCycles))
    val flags = Seq("tooMany" -> s.tooMany, "cellOverflow" -> s.cellOverflow, "largeOverflow" -> s.largeOverflow,
      "badBucket" -> s.badBucket, "sortMismatch" -> s.sortMismatch).map { case (n, b) => n -> (if (b.peek().litToBoolean) BigInt(1) else BigInt(0)) }
    val box = s.box.zipWithIndex.map { case (b, a) => s"box$a" -> b.peek().litValue }
    Run(pairs, fieldValues ++ flags ++ box + ("level" -> s.level.peek().litValue), cycles)
  }

  /** `fed`: the world's table was fed (a Feeder of `model.converted` values, see fedWorlds);
    * `ahead`: the next world's, fed while this one runs. */
  private def check(dut: BroadPhase, model: BroadPhaseModel, label: String, world: IndexedSeq[WorldSphere],
                    rng: scala.util.Random, readyOdds: Double, fed: Option[Feeder] = None, ahead: Option[Feeder] = None): Run = {
    val want = model.run(world)
    val got = run(dut, world.map(model.converted), rng, readyOdds, fed, ahead)
    val where = s"$label (${model.cfg.name}, ${world.length} spheres, level ${want.level})"
    Seq("tooMany", "cellOverflow", "largeOverflow", "badBucket", "sortMismatch").foreach { f =>
      assert(got.status(f) == 0, s"$where: $f raised")
    }
    assert(got.status("level") == want.level, s"$where: level ${got.status("level")}")
    // Box buckets: the RTL's box extents are the model's (zero for a world with no eligible
    // sphere or without box buckets, whose status never sets them).
    val box = want.stats.box.map(_.reported(BoxMapBits.extentW)).getOrElse(Seq(0L, 0L, 0L)).map(BigInt(_))
    assert((0 until 3).map(a => got.status(s"box$a")) == box, s"$where: box extents ${(0 until 3).map(a => got.status(s"box$a"))}, want $box")
    val st = want.stats
    assert(got.status("excluded") == st.excluded && got.status("large") == st.large &&
      got.status("small") == st.spheres - st.excluded - st.large, s"$where: classes ${got.status}")
    if (model.bp.lanes == 1) {
      val grid = st.gridCandidates.toInt
      val (gotGrid, gotLarge) = got.pairs.splitAt(grid)
      val firstDiff = gotGrid.zip(want.candidates.take(grid)).indexWhere { case (a, b) => a != b }
      val gridSame = firstDiff < 0 && gotGrid.length == grid // (not inline: assert would print both lists)
      assert(gridSame,
        s"$where: grid pair ${if (firstDiff < 0) gotGrid.length else firstDiff} differs (want ${grid} grid pairs)")
      val largeSame = gotLarge.sorted == want.candidates.drop(grid).sorted
      assert(largeSame, s"$where: the large pass's ${gotLarge.length} pairs differ from the model's ${want.candidates.length - grid}")
    } else {
      // Lanes interleave: the same multiset (so a doubled or lost pair fails), named by its first difference.
      val (g, w) = (got.pairs.sorted, want.candidates.sorted)
      val firstDiff = g.zip(w).indexWhere { case (a, b) => a != b }
      val same = g == w
      assert(same, s"$where: ${g.length} pairs against the model's ${w.length}" +
        (if (firstDiff >= 0) s", first difference ${g(firstDiff)} against ${w(firstDiff)}" else ""))
    }
    assert(got.status("candidates") == want.candidates.length && got.status("cells") == st.cells,
      s"$where: counters ${got.status}")
    // The prefix sum walks the buckets in use a word a cycle, with box buckets only those up to
    // the box's last place where they fit: the RTL used the model's count.
    val perWord = 1 << math.min(model.bp.wordLog2, model.bp.tableLog2(maxSpheres))
    val words = math.max(1, model.bucketsFor(world.length) / perWord)
    val walked = math.max(1, st.walkBuckets / perWord)
    val prefixCycles = walked + 3 + BucketSort.prefixStages(perWord)
    assert(got.status("cycPrefix") == prefixCycles, s"$where: prefix sum of ${got.status("cycPrefix")} cycles, want $prefixCycles " +
      s"(${st.walkBuckets} of ${model.bucketsFor(world.length)} buckets)")
    // Each lane-cycle of the grid went to one thing: the classes add up to lanes x the grid's
    // cycles, and without a large pass the entries streamed are those scanned and probed.
    val laneCycles = GridCycle.names.map(n => n -> got.status(s"lane_$n"))
    assert(laneCycles.map(_._2).sum == model.bp.lanes * got.status("cycGrid"),
      s"$where: lane-cycles ${laneCycles.mkString(", ")} against ${model.bp.lanes} lanes x ${got.status("cycGrid")} grid cycles")
    if (st.large == 0) assert(got.status("lane_streamed") == got.status("scanned") + got.status("probes"),
      s"$where: ${got.status("lane_streamed")} entries streamed, ${got.status("scanned")} scanned + ${got.status("probes")} probed")
    if (fed.isDefined) {
      // A fed table's level is chosen as it arrives: after start only the last spheres' keys and
      // the merge of the fed lanes' needs remain, and, if the clear (a word a cycle, from the
      // begin, or from the end of the world before for one begun ahead) had fewer cycles before
      // start, the rest of it; with box buckets the trackers' merge, the corners' keys and
      // BroadPhase.boxSteps cycles for the box's map. Reading the table again would take num / lanes.
      val feedWidth = dut.io.feed.length
      val merge = if (model.bp.lanes > 1) (feedWidth * (model.bp.largeMax + 1) + 1) / 2 else 0
      val clearLeft = math.max(0L, words - got.status("feedCycles").toLong)
      val keys = dut.keysLatency
      val box = if (model.bp.boxBuckets) BoxTracker.mergeLatency(model.bp.lanes) + keys + BroadPhase.boxSteps else 0
      val most = merge + clearLeft + keys + 3 + CellExponent.levelLatency + box
      assert(got.status("cycLoad") <= most, s"$where: ${got.status("cycLoad")} load cycles after a fed table, at most $most " +
        s"(${got.status("feedCycles")} cycles of feed)")
    }
    got.copy(modelStats = Some(st))
  }

  // 40 spheres at one point: three chunks of one cell, so the rescan runs twice.
  private def worlds(rng: scala.util.Random): Seq[(String, Seq[S])] = hardCases(rng, onePointSpheres = 40)

  /** Every hard case and random cloud through one BroadPhase of `bp`, fp32, printing each world's cycles. */
  private def everyHardCase(seedName: String, bp: BroadPhaseParams, tag: String): Unit = {
    val rng = Seeds.rng(seedName)
    val model = new BroadPhaseModel(ScpuConfig.fp32, bp)
    test(new BroadPhase(ScpuConfig.fp32.params, model.bp, maxSpheres)).withAnnotations(annos) { dut =>
      dut.clock.setTimeout(0)
      val runs = for ((label, w) <- worlds(rng)) yield {
        val world = bits(FloatFormat.fp32, w)
        val r = check(dut, model, label, world, rng, readyOdds = 0.7)
        println(f"[BroadPhaseSpec] $tag$label%-40s ${w.length}%4d spheres ${r.status("candidates")}%5s pairs ${r.cycles}%7d cycles, " +
          f"cell edge ${BroadPhaseParams.edge(r.status("level").toInt)}%g")
        (r.status("level").toInt, r.modelStats.get)
      }
      val levels = runs.map(_._1)
      // With coarse chunks, coarse cells taken as one chunk and groups taken cell by cell must both occur.
      val (coarse, cells) = (runs.map(_._2.coarse).sum, runs.map(_._2.cells).sum)
      if (bp.coarseChunks) assert(coarse > 0 && coarse < cells, s"$tag$coarse of $cells chunks' cells were coarse")
      else assert(coarse == 0)
      // Both kinds of cell must have been tried where both are built.
      val odd = levels.count(l => (l & 1) != 0)
      if (bp.cellSteps == 2) assert(odd > 0 && odd < levels.length, s"$tag$odd of ${levels.length} worlds had edges of 1.5 * 2^k")
      else assert(odd == 0, s"$tag$odd worlds had edges of 1.5 * 2^k with one cell step an octave")
    }
  }

  it should "find exactly the golden model's candidates in every hard case and random cloud, under back-pressure" in {
    everyHardCase("BroadPhaseSpec", BroadPhaseParams.default, "")
  }

  it should "stay exact with a four-bucket table and one-sphere chunks (every cell shares a bucket, every chunk rescans)" in {
    val rng = Seeds.rng("BroadPhaseSpec-tiny")
    val model = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.tinyTable)
    test(new BroadPhase(ScpuConfig.fp32.params, model.bp, maxSpheres)).withAnnotations(annos) { dut =>
      dut.clock.setTimeout(0)
      for ((label, w) <- worlds(rng).filter(_._2.length <= 100)) check(dut, model, label, bits(FloatFormat.fp32, w), rng, 0.5)
    }
  }

  it should "find the same candidates with several lanes, each pair once, in every hard case and random cloud" in {
    everyHardCase("BroadPhaseSpec-lanes", BroadPhaseParams.fourLanes, "four lanes: ")
  }

  it should "find the same candidates with the sort's passes two spheres a cycle, each port half the table, and 16 counters a word, in every hard case and random cloud" in {
    everyHardCase("BroadPhaseSpec-ports", BroadPhaseParams.fourLanesTwoPorts, "two sort ports: ")
  }

  // Four ports run in every default run with coarse chunks (below, and the fed table's case).
  it should "find the same candidates with the sort's counters cleared behind each scatter while the grid reads its own tables of ends (no clear between worlds after the first), in every hard case and random cloud" in {
    everyHardCase("BroadPhaseSpec-clear-behind", BroadPhaseParams.fourLanesTwoPorts.copy(clearBehind = true), "cleared behind: ")
  }

  it should "find the same candidates with the sort's passes four spheres a cycle (two sorts, each of half the table, read one after the other), in every hard case and random cloud" taggedAs (Slow) in {
    everyHardCase("BroadPhaseSpec-four-ports", BroadPhaseParams.fourLanesFourPorts, "four sort ports: ")
  }

  it should "find the same candidates with the sort's passes eight spheres a cycle (four sorts, each of a quarter of the table, read one after the other), with coarse chunks, in every hard case and random cloud" taggedAs (Slow) in {
    everyHardCase("BroadPhaseSpec-eight-ports", BroadPhaseParams.eightLanesEightPorts.copy(coarseChunks = true, chunk = 32),
      "eight sort ports: ")
  }

  it should "find the same candidates with the sort's passes 16 spheres a cycle (eight sorts, each of an eighth of the table), fed into 16 claiming lanes with box buckets, in every hard case and random cloud" taggedAs (Slow) in {
    fedWorlds("BroadPhaseSpec-16-ports", collide.afu.AfuConfig.world.broadPhase.get.copy(sortPorts = 16), 4, "16 sort ports: ", ws => ws)
  }

  it should "find the same candidates with one bucket a sphere (more cells sharing a bucket), in every hard case and random cloud" in {
    everyHardCase("BroadPhaseSpec-one-bucket", BroadPhaseParams.fourLanesFourPorts.copy(bucketsPerSphereLog2 = 0), "one bucket a sphere: ")
  }

  it should "find the same candidates with cells of edge 1.5 * 2^k too (two cell steps an octave), in every hard case and random cloud" in {
    everyHardCase("BroadPhaseSpec-cell-steps", BroadPhaseParams.fourLanesFourPorts.copy(cellSteps = 2), "edges 2^k and 1.5 * 2^k: ")
  }

  it should "find exactly the golden model's candidates with coarse chunks (a coarse cell's spheres one chunk) and hits queued a sphere deep, in every hard case and random cloud" in {
    everyHardCase("BroadPhaseSpec-coarse", BroadPhaseParams.coarse.copy(hitQueue = 1), "coarse chunks: ")
  }

  it should "find the same candidates with coarse chunks, four lanes and four sort ports (one team of four), in every hard case and random cloud" taggedAs (Slow) in {
    everyHardCase("BroadPhaseSpec-coarse-lanes", BroadPhaseParams.fourLanesFourPorts.copy(coarseChunks = true, chunk = 32), "coarse chunks, four lanes: ")
  }

  it should "find the same candidates with coarse chunks and four lanes in two teams of two (each team walking every other word), in every hard case and random cloud" taggedAs (Slow) in {
    everyHardCase("BroadPhaseSpec-coarse-teams", BroadPhaseParams.fourLanes.copy(coarseChunks = true, team = 2), "coarse chunks, teams of two: ")
  }

  it should "find the same candidates with coarse chunks and four lanes in teams of one (whole words a lane), in every hard case and random cloud" taggedAs (Slow) in {
    everyHardCase("BroadPhaseSpec-coarse-words", BroadPhaseParams.fourLanes.copy(coarseChunks = true, team = 1), "coarse chunks, teams of one: ")
  }

  it should "find the same candidates with the lanes claiming their work (units of buckets as they need them, a dense unit a bucket at a time), coarse chunks, four lanes, four sort ports and hits queued two spheres deep, in every hard case and random cloud" in {
    // Edges 2^k alone: some coarse groups overfill a chunk of 32 and are handed back (with 1.5 * 2^k none do here).
    everyHardCase("BroadPhaseSpec-claims", BroadPhaseParams.fourLanesFourPorts.copy(coarseChunks = true, chunk = 32, claims = true, hitQueue = 2),
      "claims, four lanes: ")
  }

  it should "find the same candidates with box buckets (a cell's place in the padded box) fed four a line into four claiming lanes, four sort ports, coarse chunks paired in the scan, hits drained behind, six visits ahead, in every hard case and cloud" in {
    fedWorlds("BroadPhaseSpec-box", BroadPhaseParams.fourLanesFourPorts.copy(coarseChunks = true, chunk = 32, cellSteps = 2, claims = true,
      hitQueue = 2, boxBuckets = true, drainBehind = true, lookAhead = 6, scanPairs = true), 4, "box buckets: ", ws => ws)
  }
  // One lane walks the buckets in order, so these two fail on any bucket map but the model's.
  it should "find exactly the golden model's candidates with box buckets and one lane, in the model's order, without coarse chunks" in {
    everyHardCase("BroadPhaseSpec-box-one", BroadPhaseParams.default.copy(boxBuckets = true), "box buckets, one lane: ")
  }
  // With the drain behind, a hit read from the wrong bank of indices names the wrong sphere; a scan pair out of its place
  // in the stream breaks the order: in the model's order here.
  it should "find exactly the golden model's candidates with box buckets, coarse chunks paired in the scan and one lane loading a chunk while the last one's hits leave (hits queued two deep, four visits ahead), in the model's order" in {
    everyHardCase("BroadPhaseSpec-box-coarse-one", BroadPhaseParams.default.copy(coarseChunks = true, chunk = 32, boxBuckets = true,
      hitQueue = 2, drainBehind = true, lookAhead = 4, scanPairs = true), "box buckets, coarse chunks, one lane, drain behind, scan pairs: ")
  }

  it should "stay exact with claimed work over a four-bucket table with coarse chunks of two (one unit, deferred and dealt a bucket at a time), in the model's order with one lane and with three" in {
    val rng = Seeds.rng("BroadPhaseSpec-claims-tiny")
    for (lanes <- Seq(1, 3)) {
      val model = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.tinyTable.copy(coarseChunks = true, wordLog2 = 3, chunk = 2, lanes = lanes, claims = true))
      test(new BroadPhase(ScpuConfig.fp32.params, model.bp, maxSpheres)).withAnnotations(annos) { dut =>
        dut.clock.setTimeout(0)
        for ((label, w) <- worlds(rng).filter(_._2.length <= 100)) check(dut, model, s"claims, $lanes lanes: $label", bits(FloatFormat.fp32, w), rng, 0.5)
      }
    }
  }

  it should "stay exact with coarse chunks of two over a four-bucket table (every coarse cell shares the one group)" in {
    val rng = Seeds.rng("BroadPhaseSpec-coarse-tiny")
    val model = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.tinyTable.copy(coarseChunks = true, wordLog2 = 3, chunk = 2))
    test(new BroadPhase(ScpuConfig.fp32.params, model.bp, maxSpheres)).withAnnotations(annos) { dut =>
      dut.clock.setTimeout(0)
      for ((label, w) <- worlds(rng).filter(_._2.length <= 100)) check(dut, model, label, bits(FloatFormat.fp32, w), rng, 0.5)
    }
  }

  it should "stay exact with three lanes over a four-bucket table, and with the table cut into four slices for the large pass" in {
    val rng = Seeds.rng("BroadPhaseSpec-lanes-odd")
    val tiny = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.tinyTable.copy(lanes = 3))
    test(new BroadPhase(ScpuConfig.fp32.params, tiny.bp, maxSpheres)).withAnnotations(annos) { dut =>
      dut.clock.setTimeout(0)
      for ((label, w) <- worlds(rng).filter(_._2.length <= 100)) check(dut, tiny, label, bits(FloatFormat.fp32, w), rng, 0.5)
    }
    // Ten huge spheres in chunks of two: each lane streams its quarter of the table past all five
    // chunks; two sort ports, so two large spheres often join the list in one cycle.
    val larges = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.default.copy(largeMax = 12, chunk = 2, lanes = 4, sortPorts = 2))
    test(new BroadPhase(ScpuConfig.fp32.params, larges.bp, maxSpheres)).withAnnotations(annos) { dut =>
      dut.clock.setTimeout(0)
      // Shuffled, so that both halves of the table hold huge spheres.
      val r = check(dut, larges, "ten huge", bits(FloatFormat.fp32, rng.shuffle(huge(rng, 60, 10))), rng, 0.8)
      assert(r.status("large") == 10, s"ten huge: ${r.status("large")} large spheres")
    }
  }

  it should "stay exact with no large list and with a large list too small for the huge spheres, with one lane and with three (k from the lanes' merged needs)" in {
    val rng = Seeds.rng("BroadPhaseSpec-large")
    for ((bp, label) <- Seq(BroadPhaseParams.noLarge -> "no large list", BroadPhaseParams.default.copy(largeMax = 2, chunk = 4) -> "largeMax 2",
                            BroadPhaseParams.noLarge.copy(lanes = 3) -> "no large list, three lanes",
                            BroadPhaseParams.default.copy(largeMax = 2, chunk = 4, lanes = 3, sortPorts = 2) -> "largeMax 2, three lanes")) {
      val model = new BroadPhaseModel(ScpuConfig.fp32, bp)
      test(new BroadPhase(ScpuConfig.fp32.params, bp, maxSpheres)).withAnnotations(annos) { dut =>
        dut.clock.setTimeout(0)
        check(dut, model, s"$label: five huge", bits(FloatFormat.fp32, huge(rng, 60, 5)), rng, 0.8)
        check(dut, model, s"$label: radii over 1:1000", bits(FloatFormat.fp32, mixedRadii(rng, 70)), rng, 0.8)
      }
    }
  }

  /** Worlds fed as the AFU's table writes feed them, `feedWidth` spheres a cycle, some begun and
    * fed while the world before them runs (as the AFU's run queue does, where the broad phase
    * takes that), with a random gap after it (the AFU's status write), alternating with worlds read
    * from the table (start without begin) on the same BroadPhase. */
  private def fedWorlds(seedName: String, bp: BroadPhaseParams, feedWidth: Int, tag: String, pick: Seq[(String, Seq[S])] => Seq[(String, Seq[S])]): Unit = {
    val rng = Seeds.rng(seedName)
    val model = new BroadPhaseModel(ScpuConfig.fp32, bp)
    test(new BroadPhase(ScpuConfig.fp32.params, bp, maxSpheres, feedWidth = feedWidth)).withAnnotations(annos) { dut =>
      dut.clock.setTimeout(0)
      val ws = pick(worlds(rng)).map { case (label, w) => (label, bits(FloatFormat.fp32, w)) }
      // 0: fed after the world before; 1 and 3: fed ahead (while the world before runs); 2: read.
      def mode(n: Int) = if (n == 0) 0 else n % 4
      def feeder(n: Int) = new Feeder(dut, ws(n)._2.map(model.converted), rng)
      var ahead: Option[Feeder] = None
      var aheadCount, begunAhead = 0
      for (((label, world), n) <- ws.zipWithIndex) {
        val fed = if (mode(n) == 2) None else ahead.orElse(Some(feeder(n)))
        ahead = if (n + 1 < ws.length && Set(1, 3)(mode(n + 1))) Some(feeder(n + 1)) else None
        val r = check(dut, model, label, world, rng, readyOdds = 0.7, fed = fed, ahead = ahead)
        val how = mode(n) match { case 0 => "fed  "; case 2 => "read "; case _ => "ahead" }
        println(f"[BroadPhaseSpec] $tag$label%-40s ${world.length}%4d spheres $how load ${r.status("cycLoad")}%4s of ${r.cycles}%6d cycles")
        ahead.foreach { f =>
          aheadCount += 1; if (f.begunAhead) begunAhead += 1
          for (_ <- 0 until rng.nextInt(64 + world.length)) f.step() // the gap: the clear goes on meanwhile
        }
      }
      // The broad phase must take a begin while the world before is past its level and box.
      if (feedWidth > 1) assert(aheadCount > 0 && begunAhead == aheadCount, s"$begunAhead of $aheadCount worlds begun ahead")
    }
  }

  it should "choose the level as the table is fed, a line of four spheres a cycle in any order, after the world before and while it runs, then find the same candidates (four lanes, four ports, coarse chunks), as well as after reading the table" in {
    fedWorlds("BroadPhaseSpec-fed", BroadPhaseParams.fourLanesFourPorts.copy(coarseChunks = true, chunk = 32, cellSteps = 2), 4, "fed, four a line: ", ws => ws)
  }

  // The AFU's fp16 (eight a line into 16 lanes, SLOW=1) also feeds fewer ports than lanes.
  it should "take a fed table with fewer feed ports than lanes (two of four lanes' needs merged) and with one lane" taggedAs (Slow) in {
    fedWorlds("BroadPhaseSpec-fed-two", BroadPhaseParams.fourLanesTwoPorts, 2, "fed, two a line: ", _.filter(_._2.length <= 120))
    fedWorlds("BroadPhaseSpec-fed-one", BroadPhaseParams.default, 1, "fed, one lane: ", _.filter(_._2.length <= 120))
  }

  // fp16 in every run; bf16 and fp64 (their keys are covered by SphereKeysSpec) with SLOW=1.
  for (cfg <- Seq(ScpuConfig.fp16, ScpuConfig.bf16, ScpuConfig.fp64)) {
    val name = s"match the golden model in ${cfg.name}, whose floor and margins differ"
    def body(): Unit = {
      val rng = Seeds.rng(s"BroadPhaseSpec-${cfg.name}")
      val model = new BroadPhaseModel(cfg)
      test(new BroadPhase(cfg.params, model.bp, maxSpheres)).withAnnotations(annos) { dut =>
        dut.clock.setTimeout(0)
        for ((label, w) <- worlds(rng).filter(w => Set("a uniform cloud", "radii over 1:1000", "zero radii and underflowing separations",
               "huge spheres among small ones", "near misses across cell faces")(w._1)))
          check(dut, model, label, bits(cfg.linkFormat, w), rng, 0.9)
      }
    }
    if (cfg == ScpuConfig.fp16) it should name in body() else it should name taggedAs (Slow) in body()
  }

  it should "exclude non-finite spheres, fill the table to maxSpheres, and refuse more than maxSpheres" in {
    val rng = Seeds.rng("BroadPhaseSpec-edges")
    val model = new BroadPhaseModel(ScpuConfig.fp32)
    val f = FloatFormat.fp32
    test(new BroadPhase(ScpuConfig.fp32.params, model.bp, maxSpheres)).withAnnotations(annos) { dut =>
      dut.clock.setTimeout(0)
      val w = bits(f, uniform(rng, 30))
      val nan = BigInt(java.lang.Float.floatToRawIntBits(Float.NaN).toLong & 0xffffffffL)
      val bad = w.updated(3, w(3).copy(y = nan)).updated(7, w(7).copy(r = f.infinity(false)))
      val r = check(dut, model, "two non-finite spheres", bad, rng, 1.0)
      assert(r.status("excluded") == 2)
      check(dut, model, "maxSpheres spheres", bits(f, uniform(rng, maxSpheres)), rng, 1.0)
      val over = run(dut, Seq.fill(maxSpheres + 1)(Seq.fill(4)(BigInt(0))).toIndexedSeq, rng, 1.0)
      assert(over.status("tooMany") == 1 && over.pairs.isEmpty, "more than maxSpheres must be refused")
      check(dut, model, "a world after the refusal", bits(f, uniform(rng, 20)), rng, 1.0)
    }
  }
}
