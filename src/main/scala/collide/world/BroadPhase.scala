package collide.world

import chisel3._
import chisel3.util._
import collide.util.Tree
import collide.fp.{FpParams, Pipeline}

/** What a world's run of the broad phase found and what it cost, valid once busy falls. */
class BroadPhaseStatus(kWidth: Int, countW: Int) extends Bundle {
  /** The cell level: cells of edge 2^(L/2) for even L, 1.5 * 2^((L-1)/2) for odd L. */
  val level = SInt(kWidth.W)
  val excluded = UInt(countW.W)
  val large = UInt(countW.W)
  val small = UInt(countW.W)
  val candidates = UInt(32.W)
  val cells = UInt(32.W)
  val chunks = UInt(32.W)
  val scanned = UInt(32.W)
  val probes = UInt(32.W)
  /** Cycles per pass: the first table read (the cell level), the second (classify and count), the
    * prefix sum, the scatter, the grid's candidate generation, the large pass, all. */
  val cycLoad, cycClassify, cycPrefix, cycScatter, cycGrid, cycLarge, cycTotal = UInt(32.W)
  /** The grid's lane-cycles (lanes x cycGrid) by what they went to, in GridCycle's order
    * (streamed, hitsFull, clearWait, scanStart, lookups, walk, done); a lane out of the grid
    * (idle, or in the large pass) counts as done. */
  val laneCycles = Vec(GridCycle.names.length, UInt(32.W))
  /** Box buckets' extents in units per axis, saturated at 2^16 - 1 (BroadPhaseModel.BoxMap;
    * zero without box buckets or without an eligible sphere). */
  val box = Vec(3, UInt(BoxMapBits.extentW.W))
  /** num > maxSpheres: nothing was done. */
  val tooMany = Bool()
  /** Internal checks that never fire by construction (docs/afu.md): a small sphere's cell
    * outside the guard, more large spheres than the list holds, a bucket out of range, or
    * the scatter placing a different number of spheres than the count saw. */
  val cellOverflow, largeOverflow, badBucket, sortMismatch = Bool()
}

/** The world-mode broad phase (docs/afu.md, "World mode: the broad phase"): given the
  * number of spheres, it reads the sphere table (compute-format x, y, z, r at `sphere.addr`,
  * data the cycle after) and emits every candidate pair (i < j) once on `pairs`, exactly
  * BroadPhaseModel.run's candidates. Passes: (1) read every sphere: SphereKeys' need and top
  * into CellExponent, while BucketSort clears its counters; (2) read every sphere again, keys
  * at the chosen cell level: small spheres counted into their bucket, large ones into the large list;
  * (3) the prefix sum; (4) the scatter, reading the spheres a third time; (5) the
  * CandidateGenerator, whose key records SphereKeys recomputes from the sphere table (no
  * key table: the table the AFU holds anyway is the only per-sphere RAM besides the sort's).
  * With lanes, pass 1 reads the table through every lane's port and SphereKeys, lane l its
  * slice into a CellExponent of its own, and a merge (two kept needs a cycle) gives the one
  * that chooses the level what they kept. `bp.sortPorts` spheres a cycle in passes 2 and 4: with two,
  * the first half of the table goes through port 0 of `sphere` and the second through port 1,
  * each with lane 0's or lane 1's SphereKeys and a port of the sort of its own; with four,
  * quarters through lanes 0 to 3, ports 0 and 1 into one sort (group 0: the first half) and 2
  * and 3 into another (group 1), whose buckets the generators read one after the other. With `bp.lanes` candidate generators, lane
  * l reads the table through port l of `sphere` and emits its pairs on port l of `pairs`;
  * together they are the candidates. The golden model is
  * BroadPhaseModel; the spec BroadPhaseSpec compares them pair for pair. With box buckets
  * (bp.boxBuckets) every lane's BoxTracker keeps the box of the spheres it loads, and a state
  * between the level and pass 2 turns the box into the bits of the cells' bucket map.
  */
class BroadPhaseIO(p: FpParams, bp: BroadPhaseParams, maxSpheres: Int, feedWidth: Int = 0) extends Bundle {
  val itemW = log2Ceil(maxSpheres)
  val countW = log2Ceil(maxSpheres + 1)
  /** Optional (the AFU's): a world's table is coming, `num` spheres. The spheres then arrive on
    * `feed` as they are written into the table, each once, in any order, up to `feedWidth` a
    * cycle, and `start` (with the same num) once all are in: the level is chosen and the
    * counters cleared meanwhile, so the first pass over the table is not run. Without `begin`
    * (or without feed ports, where it is ignored), `start` runs that pass. A begin is taken
    * only while `canBegin`: when idle, and (the AFU's run queue) while the current world is past
    * its level and box, where the next world's table is fed while the current one works and its
    * counters are cleared once the current one is over; its `start` comes after that. */
  val begin = Input(Bool())
  val canBegin = Output(Bool())
  val feed = Vec(feedWidth, Flipped(Valid(Vec(4, UInt(p.width.W)))))
  val start = Input(Bool())
  val num = Input(UInt(countW.W))
  val sphere = Vec(bp.lanes, new Bundle {
    val addr = Output(UInt(itemW.W))
    val data = Input(Vec(4, UInt(p.width.W))) // the cycle after
  })
  val pairs = Vec(bp.lanes, Decoupled(new WorldPair(itemW)))
  val busy = Output(Bool())
  /** Nothing moves inside without an input: not busy, no counters clearing, no fed sphere in
    * flight (the AFU lets its host skip idle cycles only then). */
  val quiet = Output(Bool())
  val status = Output(new BroadPhaseStatus(SphereKeys.kWidth(p), countW))
}

/** keysLatency: SphereKeys' registers; by default those its segments need at 200 MHz
  * (SphereKeys.latencyFor). */
class BroadPhase(p: FpParams, bp: BroadPhaseParams, maxSpheres: Int, keysLatencyOpt: Option[Int] = None, feedWidth: Int = 0) extends Module {
  val keysLatency: Int = keysLatencyOpt.getOrElse(SphereKeys.latencyFor(p, bp, 200))
  require(keysLatency >= 1, s"keysLatency must be at least 1 (the key records come a cycle after the table), got $keysLatency")
  require(maxSpheres >= 2 && maxSpheres <= (1 << 24), s"maxSpheres must be 2..2^24, got $maxSpheres")
  // The fed spheres go through lanes 0 .. feedWidth-1's SphereKeys and CellExponents.
  require(feedWidth >= 0 && feedWidth <= bp.lanes,
    s"feedWidth (spheres fed a cycle) must be 0..lanes (${bp.lanes}), got $feedWidth")
  /** Buckets the table holds: the model's cap, and no more than 2 maxSpheres can use. */
  val tableLog2: Int = bp.tableLog2(maxSpheres)
  private val largeSlots = math.max(1, bp.largeMax)
  override def desiredName =
    s"BroadPhase_${p.name}_n${maxSpheres}_b${tableLog2}_L${bp.largeMax}_k${bp.chunk}_c${bp.cellBits}_f${bp.filterFracBits}_w${bp.wordLog2}" +
      (if (bp.lanes > 1) s"_l${bp.lanes}" else "") + (if (bp.sortPorts > 1) s"_p${bp.sortPorts}" else "") +
      (if (bp.bucketsPerSphereLog2 != BroadPhaseParams.default.bucketsPerSphereLog2) s"_s${bp.bucketsPerSphereLog2}" else "") +
      (if (bp.cellSteps != BroadPhaseParams.default.cellSteps) s"_e${bp.cellSteps}" else "") + (if (bp.coarseChunks) "_x" else "") +
      s"_y$keysLatency" + (if (feedWidth > 0) s"_t$feedWidth" else "") + (if (bp.boxBuckets) "_bx" else "") + (if (bp.clearBehind) "_cb" else "") +
      (if (!bp.nearFilter) "_wf" else "")
  val io = IO(new BroadPhaseIO(p, bp, maxSpheres, feedWidth))
  private val itemW = io.itemW
  private val countW = io.countW
  private val qWidth = SphereKeys.qWidth(bp)
  private val kWidth = SphereKeys.kWidth(p)

  private val ports = bp.sortPorts
  private val groups = bp.sortGroups
  /** With lanes, the load pass reads through every lane, each into a CellExponent of its own,
    * and a merge feeds what they kept into `cellExp`, two values a cycle. */
  private val wideLoad = bp.lanes > 1
  private val laneExps = if (wideLoad) Seq.fill(bp.lanes)(Module(new CellExponent(p, bp))) else Nil
  private val cellExp = Module(new CellExponent(p, bp, if (wideLoad) 2 else 1))
  // One copy of the sorted table per lane: each lane looks up and marks its own. With two
  // groups, group g sorts the g-th half of the table, each with its own counters and entries.
  private val sorts = Seq.fill(groups)(Module(new BucketSort(bp.groupCapacity(maxSpheres), tableLog2, bp.wordLog2, bp.lanes,
    bp.portsPerSort, if (groups > 1) itemW else 0, bp.clearBehind)))
  /** The scatter is over: with clearBehind the sorts clear their cursors during the grid. */
  private val scatterOver = WireDefault(false.B)
  private val sortBusy = sorts.map(_.io.busy).reduce(_ || _)
  private val gens = Seq.tabulate(bp.lanes) { l =>
    val g = Module(new CandidateGenerator(itemW, countW, bp.cellBits, qWidth, tableLog2, bp.chunk, largeSlots,
      keyLatency = 1 + keysLatency, wordLog2 = math.min(bp.wordLog2, tableLog2), lanes = bp.lanes, groups = groups,
      coarse = bp.coarseChunks, team = bp.teamSize, claims = bp.claims, hitQueue = bp.hitQueue, boxBuckets = bp.boxBuckets,
      drainBehind = bp.drainBehind, lookAhead = bp.lookAhead, scanPairs = bp.scanPairs,
      nearBits = if (bp.nearFilter) ChunkMatcher.nearBits(bp.filterFracBits) else 0))
    g.io.lane.foreach(_ := l.U)
    g
  }
  /** Each lane recomputes its key records with a SphereKeys of its own; port p of the passes
    * uses lane p's. */
  private val laneKeys = Seq.fill(bp.lanes)(Module(new SphereKeys(p, bp, keysLatency)))
  /** The fed spheres' needs and tops, apart from the lanes' SphereKeys, which the current world
    * may be using while the next one is fed (only need, top and nonFinite are used). */
  private val feedKeys = Seq.fill(feedWidth)(Module(new SphereKeys(p, bp, keysLatency)))
  private val larges = Reg(Vec(largeSlots, new WorldKey(itemW, bp.cellBits, qWidth)))

  private object S extends ChiselEnum { val idle, fill, load, merge, settle, box, classify, prefix, scatter, generate = Value }
  private val state = RegInit(S.idle)
  private val settle = Reg(UInt(log2Ceil(CellExponent.levelLatency + 1).W))
  io.busy := state =/= S.idle && state =/= S.fill
  /** A begin taken while the current world works (the run queue): its table is fed into the
    * lane CellExponents and BoxTrackers, which the current world no longer needs once past its
    * level and box; the counters and the level's CellExponent are cleared when it is over. Only
    * with lanes (with one, the fed needs go straight into the CellExponent that holds the level). */
  val beginsAhead: Boolean = feedWidth > 0 && wideLoad
  private val pending = RegInit(false.B)
  private val pendingNum = Reg(UInt(countW.W))
  private val pastBox = state === S.classify || state === S.prefix || state === S.scatter || state === S.generate
  io.canBegin := (feedWidth > 0).B && (state === S.idle || (beginsAhead.B && pastBox && !pending))
  /** A new world starts (at begin, or at a start without one): every block forgets the last one.
    * A begin of too many spheres is not taken: its start says so. */
  private val begin = io.begin && io.canBegin && io.num <= maxSpheres.U
  private val starting = (io.start || begin) && state === S.idle
  private val beginAhead = begin && state =/= S.idle
  /** The current world is over and a world begun ahead fills next: its counters are cleared now. */
  private val handOver = WireDefault(false.B)
  /** The needs and boxes the feed fills are forgotten: at a begin, and at a start without one. */
  private val clearFed = starting || beginAhead
  /** The counters and the level are forgotten: a new world at idle, or the one begun ahead. */
  private val clearWorld = starting || handOver
  /** This world's table was fed (begin): lanes 0 .. feedWidth-1 hold its needs and tops. */
  private val fed = RegInit(false.B)
  /** Spheres are being fed: from a taken begin to its world's start. */
  private val feedOn = RegInit(false.B)

  private val num = Reg(UInt(countW.W))
  private val usedLog2 = Reg(UInt(log2Ceil(tableLog2 + 1).W))
  private val sent = Reg(Bool())
  private val st = RegInit(0.U.asTypeOf(new BroadPhaseStatus(kWidth, countW)))
  private val largeCount = RegInit(0.U(log2Ceil(largeSlots + 1).W))

  /** log2 of BroadPhaseModel.bucketsFor(n), one-hot: the least t with 2^t >= n 2^bucketsPerSphereLog2,
    * capped at the table (0 for n = 0). From compares of n against constants, so no subtraction,
    * leading-one search or add lies between a world's size and its first registers. */
  private def bucketsLog2OneHot(n: UInt): Seq[(Bool, Int)] = {
    // above(c): ceil(log2 n) > c, i.e. n > 2^c (a thermometer); ceil(log2 n) = c exactly
    // where above(c - 1) holds and above(c) does not.
    val above = (0 to countW).map(c => n > (BigInt(1) << c).U)
    val byCeil = (0 to countW).map { c =>
      val is = (if (c == 0) n =/= 0.U else above(c - 1)) && !above(c)
      is -> math.min(c + bp.bucketsPerSphereLog2, tableLog2)
    }
    ((n === 0.U) -> 0) +: byCeil
  }
  /** The buckets' log2 and their count, 2^log2, both from one one-hot of n. */
  private def bucketsOf(n: UInt): (UInt, UInt) = {
    val oh = bucketsLog2OneHot(n)
    (Mux1H(oh.map { case (b, t) => b -> t.U(log2Ceil(tableLog2 + 1).W) }),
      Mux1H(oh.map { case (b, t) => b -> (BigInt(1) << t).U((tableLog2 + 1).W) }))
  }

  // Lane l's slice of the table, [cut(l), cut(l + 1)), c_l = floor(l 2^16 / lanes): the slices
  // tile the table, each bound within num / 2^16 + 1 of num l / lanes (a multiply by a
  // constant, where an exact cut would need a divider). The load pass and the large pass use them.
  private def cutOf(n: UInt, m: Int): UInt =
    if (m == 0) 0.U else if (m == bp.lanes) n else (timesConst(n, (m.toLong << 16) / bp.lanes) >> 16).pad(countW)(countW - 1, 0)
  /** n k for a constant k, as a tree of adds of n's shifts (one per bit of k): a world's size
    * reaches its lanes' bounds without a multiplier (16 lanes: k = m 2^12, at most three adds in two levels). */
  private def timesConst(n: UInt, k: Long): UInt =
    Tree.reduce((0 until 64).filter(b => ((k >> b) & 1) == 1).map(b => n << b))(_ +& _)
  private def cut(m: Int): UInt = cutOf(num, m)

  // --- passes 1, 2 and 4: read the sphere table through SphereKeys --------------------------
  // The load pass: lane l reads its slice (with one lane, the whole table). Classify and
  // scatter: port q reads [from(q), to(q)) = [floor(q num / P), floor((q + 1) num / P)): the
  // whole table with one port, halves with two, quarters with four, through lane q's sphere
  // port and SphereKeys. (In pass 5 the generators read it, for their key records.)
  private def from(port: Int): UInt =
    if (port == 0) 0.U else (timesConst(num, port) >> log2Ceil(ports)).pad(countW)(countW - 1, 0)
  private def to(port: Int): UInt = if (port == ports - 1) num else from(port + 1)
  private val inPass = state === S.load || state === S.classify || state === S.scatter
  private val i = Reg(Vec(bp.lanes, UInt(countW.W))) // the next sphere each lane reads
  // Each lane's bound, set with its start (setUp: the load pass's slice; restart: the port's
  // range, none past the ports), so no multiply lies between a lane's count and its read.
  private val hi = Reg(Vec(bp.lanes, UInt(countW.W)))
  private val laneLeft = VecInit.tabulate(bp.lanes)(l => i(l) < hi(l)) // a read left in the lane's range
  private val reading = VecInit.tabulate(bp.lanes)(l => inPass && laneLeft(l))
  // The reads issued last cycle: SphereKeys' inputs, counted into `inflight` from registers.
  private val issued = RegNext(reading, VecInit(Seq.fill(bp.lanes)(false.B)))
  private val inflight = RegInit(0.U(log2Ceil(bp.lanes * (keysLatency + 2) + 1).W)) // reads not yet out of SphereKeys
  /** Keys between SphereKeys and the sorts (CellHash's registers). */
  private val hashBusy = WireDefault(false.B)
  // No lane has a read left, registered: the lanes' compares (carry chains) then do not lead the
  // pass-done logic into the state machine. It lags by one cycle where it matters at all (the
  // last read's keys are still in SphereKeys), and a cycle that sets the lanes' ranges clears it.
  private val settingLanes = WireDefault(false.B)
  private val lanesDone = RegNext(!settingLanes && !laneLeft.asUInt.orR, false.B)
  private val passDone = lanesDone && !issued.asUInt.orR && inflight === 0.U && !hashBusy
  private val level = cellExp.io.level
  private def large(o: SphereKeys): Bool = !o.io.out.nonFinite && !o.io.out.needNone && o.io.out.need > level
  private def record(o: SphereKeys): KeyRecord = {
    val r = Wire(new KeyRecord(bp.cellBits, qWidth))
    r.cell := o.io.out.cell; r.q := o.io.out.q; r.qr := o.io.out.qr; r.large := large(o); r.excluded := o.io.out.nonFinite
    r
  }
  /** What port q's SphereKeys gives this cycle, and for which sphere. */
  private case class Keyed(o: SphereKeys, index: UInt) {
    def out = o.io.out
    def valid: Bool = out.valid
    def isLarge: Bool = large(o)
    def isSmall: Bool = !out.nonFinite && !isLarge
  }
  private val filling = state === S.fill
  // The load pass (its last spheres leave SphereKeys up to its latency after it).
  private val loading = state === S.load
  for ((lk, l) <- laneKeys.zipWithIndex) {
    io.sphere(l).addr := Mux(state === S.generate, gens(l).io.keyAddr, i(l)(itemW - 1, 0))
    lk.io.in.valid := issued(l)
    lk.io.in.sphere := io.sphere(l).data
    // need and top do not depend on the level
    lk.io.in.level := Mux(loading, 0.S, level)
  }
  private val fedIn = io.feed.map(f => f.valid && feedOn)
  for (((fk, f), in) <- feedKeys.zip(io.feed).zip(fedIn)) {
    fk.io.in.valid := in
    fk.io.in.sphere := f.bits
    fk.io.in.level := 0.S
  }
  /** Fed spheres not yet out of their SphereKeys. */
  private val feedInflight = RegInit(0.U(log2Ceil(math.max(1, feedWidth) * (keysLatency + 2) + 1).W))
  if (feedWidth > 0) feedInflight := feedInflight + PopCount(fedIn) - PopCount(feedKeys.map(_.io.out.valid))
  private val keyed = (0 until ports).map { q =>
    Keyed(laneKeys(q), Pipeline(RegNext(i(q)(itemW - 1, 0)), keysLatency, true.B))
  }
  inflight := inflight + PopCount(issued) - PopCount(laneKeys.map(_.io.out.valid))
  io.quiet := !io.busy && !sortBusy && feedInflight === 0.U
  for ((g, lk) <- gens.zip(laneKeys)) g.io.keyData := record(lk)

  // --- box buckets: the world's box, kept by every lane as it loads (BroadPhaseModel.boxMap) ---
  private val unitBits = bp.cellBits // a unit (a cell, or a coarse cell) and the origin below it fit a cell's width
  /** The box's map, set in state box (after the level) and used by every bucket after it. */
  private val boxMap = Reg(new BoxMapBits(unitBits, tableLog2))
  private val boxExtent = RegInit(VecInit(Seq.fill(3)(0.U(BoxMapBits.extentW.W))))
  /** The corners' keys come keysLatency cycles into state box, after the trackers' merge has
    * settled; the map takes BroadPhase.boxSteps more. */
  private val boxFirst = BoxTracker.mergeLatency(bp.lanes) + keysLatency
  private val boxCycle = RegInit(0.U(log2Ceil(boxFirst + BroadPhase.boxSteps).W))
  /** The box's map is final: classify may start. */
  private val boxDone = WireDefault(true.B)
  /** Buckets in use: 2^usedLog2. */
  /** The buckets in use, 2^usedLog2, a register of its own (set with usedLog2), so the box's
    * fit compares it with no shift before the compare. */
  private val used = Reg(UInt((tableLog2 + 1).W))
  private val wordLog2 = math.min(bp.wordLog2, tableLog2)
  /** The buckets the prefix sum and the walk cover (BroadPhaseModel.walkBuckets): those in use,
    * or, where the box's places fit them, the places' buckets rounded up to a word. */
  private val walkBuckets = Reg(UInt((tableLog2 + 1).W))
  if (bp.boxBuckets) {
    val trackers = laneKeys.zipWithIndex.map { case (lk, l) =>
      val t = Module(new BoxTracker(p))
      t.io.clear := clearFed
      t.io.in.valid := lk.io.in.valid && loading
      t.io.in.bits := lk.io.in.sphere
      if (l < feedWidth) when(fedIn(l)) { t.io.in.valid := true.B; t.io.in.bits := io.feed(l).bits }
      t
    }
    // Registered: the trackers are final at least two cycles before state box (the load pass
    // ends once its last sphere is out of SphereKeys, a cycle after its tracker took it), and the
    // merge (settled in BoxTracker.mergeLatency cycles, counted in boxFirst) then feeds the
    // corners' SphereKeys from a register, not through its compares.
    val merged = BoxTracker.merge(trackers)
    val anyBox = RegNext(merged._1)
    val lo = RegNext(merged._2)
    val hi = RegNext(merged._3)
    // The units of the least and greatest corner at the level, keysLatency cycles into state box.
    val corners = Seq(lo, hi).map { keys =>
      val k = Module(new SphereKeys(p, bp, keysLatency))
      k.io.in.valid := true.B
      k.io.in.sphere := VecInit(keys.map(BoxTracker.bits) :+ 0.U(p.width.W))
      k.io.in.level := level
      k.io.out.cell.map(c => if (bp.coarseChunks) c >> 1 else c)
    }
    // Extents in units (at least one: hi >= lo), exact in a cell's width plus one.
    // The map takes boxSteps cycles after the corners come, one operation a cycle between
    // registers (an extent; its saturation and the factors; each multiply alone, as a DSP
    // block with registered operands is most of a 5 ns cycle; the sum; the words; the compare).
    val extent = Reg(Vec(3, UInt((unitBits + 2).W)))
    val origin = Reg(Vec(3, SInt(unitBits.W)))
    val satW = tableLog2 + 2
    val sat0p2 = Reg(UInt((satW + 1).W))
    val factX = Reg(UInt((satW + 1).W)) // sat(0) + 1
    val factY = Reg(UInt((satW + 1).W)) // sat(1) + 1
    val factZ = Reg(UInt((satW + 1).W)) // sat(2) + 2
    // Places from 2^satW up cannot fit the table: past a product's low satW bits only "big" is
    // kept (an OR, no carry chain), so the sum and the compares after it are satW bits wide.
    val placesXY = Reg(UInt((2 * satW + 2).W))
    val placesP = Reg(UInt((2 * satW + 1).W))
    val places = Reg(UInt((satW + 2).W))
    val big = Reg(Bool())
    val words = Reg(UInt((satW + 2 + (if (bp.coarseChunks) 3 else 0)).W))
    val fits = Reg(Bool())
    val groupLog2 = if (bp.coarseChunks) 3 else 0
    val hashBits = if (bp.coarseChunks) Mux(usedLog2 > 3.U, usedLog2 - 3.U, 0.U) else usedLog2
    val hashCap = Reg(UInt((tableLog2 + 1).W)) // 2^hashBits, registered before the compare needs it
    val perWord = 1 << wordLog2
    def at(k: Int): Bool = boxCycle === (boxFirst + k).U
    boxDone := at(BroadPhase.boxSteps - 1)
    when(state === S.box) {
      boxCycle := boxCycle + 1.U
      when(at(0)) {
        for (a <- 0 until 3) {
          extent(a) := (corners(1)(a) -& corners(0)(a) +& 1.S).asUInt
          origin(a) := corners(0)(a) - 1.S
        }
      }
      when(at(1)) {
        boxMap.origin := origin
        boxMap.rx := (extent(0) + 1.U)(tableLog2 - 1, 0)
        boxMap.rxy := (extent(1) + 1.U)(tableLog2 - 1, 0) // times rx two cycles on
        val most = ((1 << BoxMapBits.extentW) - 1).U
        // For the fit only, each extent saturated past the table (its places would not fit anyway).
        val sat = extent.map(e => Mux(e >= (1 << (tableLog2 + 1)).U, (1 << (tableLog2 + 1)).U, e)(satW - 1, 0))
        for (a <- 0 until 3) boxExtent(a) := Mux(anyBox, Mux(extent(a) >= most, most, extent(a)), 0.U)
        factX := sat(0) +& 1.U; factY := sat(1) +& 1.U; factZ := sat(2) +& 2.U; sat0p2 := sat(0) +& 2.U
        hashCap := (1.U((tableLog2 + 1).W) << hashBits)(tableLog2, 0)
      }
      when(at(2)) { placesXY := factX * factY }
      when(at(3)) {
        boxMap.rxy := (boxMap.rxy * boxMap.rx)(tableLog2 - 1, 0)
        big := placesXY(placesXY.getWidth - 1, satW).orR
        placesP := placesXY(satW - 1, 0) * factZ
      }
      when(at(4)) {
        big := big || placesP(placesP.getWidth - 1, satW).orR
        places := placesP(satW - 1, 0) +& sat0p2
      }
      when(at(5)) {
        // The places' buckets rounded up to a word, where they fit the buckets in use.
        fits := anyBox && !big && places <= hashCap
        words := ((places << groupLog2) + (perWord - 1).U) >> wordLog2
      }
      when(at(6)) {
        when(fits && (words << wordLog2) < used) { walkBuckets := words << wordLog2 }
        boxCycle := 0.U
      }
    }.otherwise { boxCycle := 0.U }
  }
  private val boxArg = if (bp.boxBuckets) Some(boxMap) else None
  for (g <- gens) g.io.box.foreach(_ := boxMap)

  private def feed(ce: CellExponentIn, valid: Bool, o: SphereKeys): Unit = {
    ce.valid := valid
    ce.need := o.io.out.need; ce.needNone := o.io.out.needNone
    ce.top := o.io.out.top; ce.topNone := o.io.out.topNone
    ce.nonFinite := o.io.out.nonFinite
  }
  /** Lane l's needs: from its SphereKeys in the load pass, or from its feed's as the table is fed. */
  private def needsOf(ce: CellExponentIn, l: Int): Unit = {
    feed(ce, laneKeys(l).io.out.valid && loading, laneKeys(l))
    if (l < feedWidth) when(feedKeys(l).io.out.valid) { feed(ce, true.B, feedKeys(l)) }
  }
  cellExp.io.clear := clearWorld
  private val mergeSlots = bp.largeMax + 1
  private val mergeItems = bp.lanes * mergeSlots
  private val m = Reg(UInt(log2Ceil(mergeItems + 2).W)) // the merge's next item: lane m / slots, slot m % slots
  /** A fed world's needs are in lanes 0 .. feedWidth-1 alone: the merge stops after them. */
  private val mergeEnd = if (feedWidth > 0) Mux(fed, (feedWidth * mergeSlots).U, mergeItems.U) else mergeItems.U
  /** mergeEnd - m, counted down: the merge's end is a test of a register, not an add and a compare. */
  private val mergeLeft = Reg(UInt(log2Ceil(mergeItems + 2).W))
  if (!wideLoad) needsOf(cellExp.io.in.head, 0)
  else {
    for ((e, l) <- laneExps.zipWithIndex) {
      e.io.clear := clearFed
      needsOf(e.io.in.head, l)
    }
    // Every lane's filled slots, each with the lane's top (the largest of them is the top).
    val needs = VecInit(laneExps.flatMap(e => e.io.kept))
    val filled = VecInit(laneExps.flatMap(e => (0 until mergeSlots).map(j => j.U < e.io.used)))
    val tops = VecInit(laneExps.flatMap(e => Seq.fill(mergeSlots)(e.io.top)))
    val anyTops = VecInit(laneExps.flatMap(e => Seq.fill(mergeSlots)(e.io.anyTop)))
    require(cellExp.io.in.length <= 2, "the merge feeds two values a cycle")
    for ((ce, d) <- cellExp.io.in.zipWithIndex) {
      // m counts by two from 0, so m + d is m with its low bit set, and m + d < mergeEnd is
      // d < mergeLeft: no add or compare before the merge's valid.
      val at = m | d.U
      val idx = at(log2Ceil(mergeItems) - 1, 0)
      ce.valid := state === S.merge && mergeLeft > d.U && filled(idx)
      ce.need := needs(idx); ce.needNone := false.B // an empty need is minK, as the lane kept it
      ce.top := tops(idx); ce.topNone := !anyTops(idx)
      ce.nonFinite := false.B
    }
  }

  private val classifying = state === S.classify
  // The ports' counts are registered and added a cycle later (the need's compare, the count and
  // a 32-bit add in one cycle were a long path); the last lands in the prefix state's first cycle.
  private def countOf(f: Keyed => Bool): UInt = RegNext(countBits(keyed.map(kd => classifying && kd.valid && f(kd))), 0.U)
  st.excluded := st.excluded + countOf(_.out.nonFinite)
  st.small := st.small + countOf(_.isSmall)
  when(classifying) {
    when(keyed.map(kd => kd.valid && kd.isSmall && kd.out.cellOverflow).reduce(_ || _)) { st.cellOverflow := true.B }
  }
  // Large spheres join the list in port order (the list's order does not matter: two large
  // spheres meet once, from the lower index), a cycle after SphereKeys gives them: the ports'
  // large flags and keys are registered (the need's compare, the ports' count, the slot's add
  // and the list's write in one cycle were the broad phase's slowest path). The next cycle the
  // cycle's large keys are packed in port order (packed(j): the j-th, chosen by the registered
  // flags alone) and slot s takes packed(s - largeCount), a mux on a register: no add on the way.
  private val largeHere = RegNext(VecInit(keyed.map(kd => classifying && kd.valid && kd.isLarge)),
    VecInit(Seq.fill(ports)(false.B)))
  private val largeKeys = RegNext(VecInit(keyed.map(kd => WorldKey(itemW, kd.index, record(kd.o)))))
  // Their count, registered with them (countOf): no count lies before the list's add.
  private val largeNow = countOf(_.isLarge)
  private val packed = VecInit.tabulate(ports) { j =>
    Mux1H((j until ports).map(q => (largeHere(q) && countBits(largeHere.take(q)) === j.U) -> largeKeys(q)))
  }
  for (s <- 0 until bp.largeMax) {
    val js = (0 until ports).filter(j => s - j >= 0)
    val takes = js.map(j => largeCount === (s - j).U && largeNow > j.U)
    when(VecInit(takes).asUInt.orR) { larges(s) := Mux1H(takes, js.map(packed(_))) }
  }
  private val largeNew = largeCount +& largeNow
  private val largeKept = Mux(largeNew > bp.largeMax.U, bp.largeMax.U, largeNew)
  // st.large counts with largeCount from zero in each world (both cleared at its start), so it
  // is set to the count, not added to.
  when(largeHere.asUInt.orR) { st.large := largeKept; largeCount := largeKept }
  // The overflow is a sticky status bit: set a cycle on, from a register (the count's add and
  // compare then end at a plain register, with no enable logic after them).
  when(RegNext(largeHere.asUInt.orR && largeNew > bp.largeMax.U, false.B)) { st.largeOverflow := true.B }

  private val slack = {
    // BroadPhaseModel.boxSlack: 1 + max(1, 2^(errorExp + F - k)), k = ceil(level / 2),
    // saturated to the width. Registered twice (the exponent, then the slack): the level is
    // set in the load pass, the slack used in the grid, passes later.
    val e = RegNext(bp.errorExp(p).S +& bp.filterFracBits.S -& SphereKeys.filterExp(level))
    val big = e >= (qWidth - 1).S
    RegNext(Mux(e < 0.S, 2.U, Mux(big, ((BigInt(1) << qWidth) - 1).U, 1.U +& (1.U << e.asUInt(log2Ceil(qWidth) - 1, 0)))))
  }
  for (sort <- sorts) {
    sort.io.usedLog2 := usedLog2
    sort.io.walkBuckets := walkBuckets
    sort.io.clear := clearWorld
    sort.io.prefix := state === S.prefix && !sent
    sort.io.scrub.foreach(_ := scatterOver)
  }
  // Port q is port q % portsPerSort of group q / portsPerSort's sort.
  private val sortIns = sorts.flatMap(_.io.in)
  // A key reaches its sort CellHash.latency cycles after SphereKeys gives it, with its bucket.
  private val hashing = for ((in, kd) <- sortIns.zip(keyed)) yield {
    val v = Seq.iterate(kd.valid && (state === S.classify || state === S.scatter) && kd.isSmall, CellHash.latency + 1)(
      RegNext(_, false.B))
    in.valid := v.last
    in.bits.scatter := ShiftRegister(state === S.scatter, CellHash.latency)
    in.bits.bucket := CellHash(kd.out.cell, tableLog2, usedLog2, bp.coarseChunks, boxArg)
    in.bits.item := ShiftRegister(kd.index, CellHash.latency)
    assert(!in.valid || in.ready, "BroadPhase: the sort was not ready (a pass overlapped its clear or prefix)")
    v.tail.reduce(_ || _)
  }
  hashBusy := hashing.reduce(_ || _)
  for ((gen, l) <- gens.zipWithIndex) {
    val entryGroup = RegNext(gen.io.entry.group)
    for ((sort, g) <- sorts.zipWithIndex) {
      val lk = sort.io.lookup(l)
      lk.bucket := gen.io.lookup.bucket
      gen.io.lookup.begin(g) := lk.begin; gen.io.lookup.end(g) := lk.end
      gen.io.lookup.word(g) := lk.word
      // Positions in a group's table are below its capacity.
      sort.io.entry(l).addr := gen.io.entry.addr(sort.io.posW - 1, 0)
      sort.io.mark(l).valid := gen.io.mark.valid && gen.io.mark.bits.group === g.U
      sort.io.mark(l).bits.addr := gen.io.mark.bits.addr(sort.io.posW - 1, 0)
      sort.io.mark(l).bits.item := gen.io.mark.bits.item
    }
    // The entry read comes back from the group the stream asked.
    def fromGroup[T <: Data](f: BucketSort => T): T = if (groups == 1) f(sorts.head) else VecInit(sorts.map(f))(entryGroup)
    gen.io.entry.item := fromGroup(_.io.entry(l).item)
    gen.io.entry.mark := fromGroup(_.io.entry(l).mark)

    gen.io.start := state === S.generate && !sent
    gen.io.usedLog2 := usedLog2
    gen.io.walkBuckets := walkBuckets
    gen.io.slack := slack
    gen.io.larges := larges
    gen.io.largeCount := largeCount
    // Lane l streams its slice of the table past the large list.
    gen.io.largeFrom := cut(l)
    gen.io.largeTo := cut(l + 1)
    io.pairs(l) <> gen.io.pairs
  }
  /** The number of set bits, of full and half adders in gates: yosys maps a `+` (PopCount's) to a
    * carry chain, whose entry alone costs more than a LUT; gates are left to the LUT mapper. */
  private def countBits(bits: Seq[Bool]): UInt = {
    var cols: Seq[Seq[Bool]] = Seq(bits)
    while (cols.exists(_.length > 1)) {
      val nx = Array.fill(cols.length + 1)(Seq.empty[Bool])
      for ((c, wt) <- cols.zipWithIndex; g <- c.grouped(3)) g match {
        case Seq(a, b, d) => nx(wt) :+= (a ^ b ^ d); nx(wt + 1) :+= ((a && b) || (a && d) || (b && d))
        case Seq(a, b) => nx(wt) :+= (a ^ b); nx(wt + 1) :+= (a && b)
        case Seq(a) => nx(wt) :+= a
      }
      cols = nx.toSeq.reverse.dropWhile(_.isEmpty).reverse
    }
    if (cols.isEmpty || cols.head.isEmpty) 0.U else Cat(cols.reverse.map(_.headOption.getOrElse(false.B)))
  }
  // --- claims: the lanes take work from shared counters as they need it ---------------------
  // Units of buckets (coarse groups, or words) in order, several lanes a cycle; a unit that is
  // not one coarse chunk comes back deferred, and its buckets are then dealt one a cycle, before
  // any further unit (the dense work first, in pieces, so no lane is left with it at the end).
  if (bp.claims) {
    val gWordLog2 = math.min(bp.wordLog2, tableLog2)
    val uLog2 = CandidateGenerator.unitLog2(gWordLog2, bp.coarseChunks)
    val w = CandidateGenerator.claimW(tableLog2)
    val uW = tableLog2 - uLog2 + 1
    // Units to walk: the walked buckets'.
    val units = BucketSort.spans(walkBuckets, uLog2)
    val next = Reg(UInt((uW + log2Ceil(bp.lanes + 1)).W))
    /** Units not yet granted, units - next: a unit lane's grant is then a compare of its small
      * rank against it, with no add before the compare (next + count < units after the lanes'
      * prefix counts was the broad phase's slowest path). */
    val left = Reg(UInt(uW.W))
    val held = RegInit(VecInit(Seq.fill(bp.lanes)(false.B)))
    val heldUnit = RegInit(VecInit(Seq.fill(bp.lanes)(false.B))) // held, and a whole unit
    val grant = Reg(Vec(bp.lanes, UInt(w.W)))
    val grantSingle = Reg(Vec(bp.lanes, Bool()))
    // Deferred units: each holds more than a chunk, so at most maxSpheres / (chunk + 1) of them.
    val deferCap = math.max(1, math.min(1 << (tableLog2 - uLog2), maxSpheres / (bp.chunk + 1)))
    val deferred = Mem(deferCap, UInt(uW.W))
    val dCount = Reg(UInt(log2Ceil(deferCap + 1).W))
    val dNext = Reg(UInt((log2Ceil(deferCap + 1) + uLog2).W)) // deferred buckets dealt
    /** Deferred buckets not yet dealt, (dCount << uLog2) - dNext, and whether any is: a register,
      * not a compare, ahead of the lanes' counts. */
    val dRem = Reg(UInt((log2Ceil(deferCap + 1) + uLog2).W))
    val dLeft = RegInit(false.B)
    for ((g, h) <- gens.zip(held)) when(g.io.take.get) { h := false.B }
    // One deferral accepted a cycle, the lowest lane's.
    val defers = VecInit(gens.map(_.io.defer.get.valid))
    val dLane = PriorityEncoderOH(defers.asUInt)
    for ((g, l) <- gens.zipWithIndex) g.io.deferOk.get := dLane(l)
    val deferNow = defers.asUInt.orR
    when(deferNow) {
      deferred.write(dCount, Mux1H(dLane, gens.map(_.io.defer.get.bits >> uLog2)))
      dCount := dCount + 1.U
    }
    assert(!deferNow || dCount < deferCap.U, "BroadPhase: more deferred units than can hold more than a chunk")
    assert(state =/= S.generate || !sent || dLeft === (dNext < (dCount << uLog2)), "BroadPhase: the deferred buckets left lost count")
    // A lane that needs work and holds none gets some two cycles later (a cycle more than with
    // one stage, which was the broad phase's slowest path), through two stages. Stage 1 (this cycle): the lowest such lane is dealt a deferred bucket if one is
    // left, the others (in lane order) are ranked among those asking for units; the ranks are
    // counted in gates (countBits), and registered (unitAsk, rank, asked) with the bucket read
    // (dealt). Stage 2 (next cycle): lane l's unit is next + rank(l) if rank(l) < left, set into
    // held and grant. A lane in stage 2 asks for nothing more until its claim is held (or refused).
    val unitAsk = RegInit(VecInit(Seq.fill(bp.lanes)(false.B)))
    val singleAsk = RegInit(VecInit(Seq.fill(bp.lanes)(false.B)))
    val rankW = math.max(1, log2Ceil(bp.lanes))
    val rank = Reg(Vec(bp.lanes, UInt(rankW.W)))
    val asked = Reg(UInt(log2Ceil(bp.lanes + 1).W))
    val dealt = Reg(UInt(w.W))
    val wants = VecInit.tabulate(bp.lanes)(l => gens(l).io.need.get && !held(l) && !unitAsk(l) && !singleAsk(l))
    val toSingle = VecInit.tabulate(bp.lanes)(l => dLeft && wants(l) && !wants.take(l).foldLeft(false.B)(_ || _))
    val toUnit = VecInit.tabulate(bp.lanes)(l => wants(l) && !toSingle(l))
    val single = dLeft && wants.asUInt.orR
    val dUnit = deferred.read(dNext >> uLog2)
    val dBucket = if (uLog2 == 0) dUnit else Cat(dUnit, dNext(uLog2 - 1, 0))
    unitAsk := toUnit
    singleAsk := toSingle
    for (l <- 0 until bp.lanes) rank(l) := countBits(toUnit.take(l))
    asked := countBits(toUnit)
    when(single) { dealt := dBucket; dNext := dNext + 1.U }
    dRem := dRem + Mux(deferNow, (1 << uLog2).U, 0.U) - single
    // dRem's next value is not zero: written as compares against constants (LUTs, no carry chain).
    dLeft := deferNow || dRem(dRem.getWidth - 1, 1).orR || (dRem === 1.U && !single)
    for (l <- 0 until bp.lanes) {
      when(singleAsk(l)) { held(l) := true.B; heldUnit(l) := false.B; grant(l) := dealt; grantSingle(l) := true.B }
      when(unitAsk(l)) {
        val ok = rank(l) < left
        held(l) := ok; heldUnit(l) := ok; grant(l) := (next + rank(l)) << uLog2; grantSingle(l) := false.B
      }
      gens(l).io.claim.get.valid := held(l)
      gens(l).io.claim.get.bits.bucket := grant(l)
      gens(l).io.claim.get.bits.single := grantSingle(l)
    }
    // One subtraction both tests and counts down: its borrow says more were asked than are left.
    val sw = uW max asked.getWidth
    val rest = left.pad(sw) -& asked.pad(sw)
    val short = rest(sw)
    val granted = Mux(short, left, asked)
    next := next + granted
    left := Mux(short, 0.U, rest(uW - 1, 0))
    // Nothing left: every unit granted and resolved (walked, or deferred and every bucket dealt),
    // and no deferred bucket on its way through stage 2 (a unit lane there gets one only while
    // left is not zero).
    val out = left === 0.U && !dLeft && !singleAsk.asUInt.orR && !gens.map(_.io.unresolved.get).reduce(_ || _) &&
      !heldUnit.zip(held).map { case (u, h) => u && h }.reduce(_ || _)
    gens.foreach(_.io.claimsOut.get := out)
    // A new grid: every claim dropped and the counts from zero (the lanes look the cycle after).
    when(state =/= S.generate || !sent) {
      next := 0.U; left := units; dCount := 0.U; dNext := 0.U; dRem := 0.U; dLeft := false.B
      held.foreach(_ := false.B); unitAsk.foreach(_ := false.B); singleAsk.foreach(_ := false.B)
    }
  }
  st.candidates := st.candidates + PopCount(io.pairs.map(_.fire))
  private def laneSum(f: CandidateGenerator => UInt): UInt = gens.map(f).reduce(_ +& _)(31, 0)
  private val gensBusy = gens.map(_.io.busy).reduce(_ || _)
  // A cycle of the large pass: some lane in it and none still in the grid.
  private val largeOnly = gens.map(g => !g.io.busy || g.io.inLargePass).reduce(_ && _)

  // --- sequencing ----------------------------------------------------------------------------
  private def advance(): Unit = for (l <- 0 until bp.lanes) when(reading(l)) { i(l) := i(l) + 1.U }
  /** Classify and scatter: the ports' halves; other lanes read nothing. */
  private def restart(): Unit = {
    settingLanes := true.B
    for (l <- 0 until bp.lanes) { i(l) := (if (l < ports) from(l) else 0.U); hi(l) := (if (l < ports) to(l) else 0.U) }
  }
  // The broad phase's own cycles: from start (a fed table's arrival is the link's time).
  when(state =/= S.idle && !filling) { st.cycTotal := st.cycTotal + 1.U }
  /** A world of n spheres: its sizes and, for a fed table, a load pass that reads nothing (each
    * lane starts at its slice's end). */
  private def setUp(n: UInt, read: Bool): Unit = setUp(n, (0 to bp.lanes).map(cutOf(n, _)), read)
  /** The same with the lanes' slices given (`cuts`, cut(0) to cut(lanes) of n). */
  private def setUp(n: UInt, cuts: Seq[UInt], read: Bool): Unit = {
    val (log2, count) = bucketsOf(n)
    num := n; usedLog2 := log2; used := count; largeCount := 0.U; settingLanes := true.B
    walkBuckets := count // the box may cut it
    for (l <- 0 until bp.lanes) { i(l) := Mux(read, cuts(l), cuts(l + 1)); hi(l) := cuts(l + 1) }
    fed := !read
  }
  // A world begun ahead has its slices computed at its begin, so its hand-over loads registers
  // (the shift-and-add products were the broad phase's longest path, into the read positions).
  private val pendingCuts = Reg(Vec(bp.lanes + 1, UInt(countW.W)))
  when(io.start && (state === S.idle || filling)) { feedOn := false.B }
  when(beginAhead) {
    pending := true.B; pendingNum := io.num; feedOn := true.B
    pendingCuts := VecInit((0 to bp.lanes).map(cutOf(io.num, _)))
  }
  switch(state) {
    is(S.idle) {
      when(io.start) {
        val z = WireDefault(0.U.asTypeOf(st))
        setUp(io.num, true.B)
        when(io.num > maxSpheres.U) { z.tooMany := true.B; st := z }.otherwise { st := z; state := S.load }
      }.elsewhen(begin) {
        setUp(io.num, false.B); feedOn := true.B; state := S.fill
      }
    }
    is(S.fill) {
      // The level is chosen as the spheres arrive; the load pass then only waits for the last of
      // them to leave SphereKeys and for the clear, and the merge takes the fed lanes' needs.
      // The status is the last world's until this start (the AFU writes it after busy falls,
      // while the next world may be fed).
      when(io.start) { state := S.load; st := 0.U.asTypeOf(st) }
    }
    is(S.load) {
      st.cycLoad := st.cycLoad + 1.U
      advance()
      when(passDone && feedInflight === 0.U && !sortBusy) {
        if (wideLoad) { state := S.merge; m := 0.U; mergeLeft := mergeEnd } else { state := S.settle; settle := 0.U }
      }
    }
    is(S.merge) {
      st.cycLoad := st.cycLoad + 1.U
      m := m + 2.U; mergeLeft := mergeLeft - 2.U
      when(mergeLeft <= 2.U) { state := S.settle; settle := 0.U } // the last values land this cycle
    }
    is(S.settle) {
      // The level's own registers (CellExponent.levelLatency) take in the last needs.
      st.cycLoad := st.cycLoad + 1.U
      settle := settle + 1.U
      when(settle === (CellExponent.levelLatency - 1).U) {
        if (bp.boxBuckets) state := S.box else { state := S.classify; restart() }
      }
    }
    is(S.box) {
      st.cycLoad := st.cycLoad + 1.U
      when(boxDone) { state := S.classify; restart(); st.box := boxExtent }
    }
    is(S.classify) {
      st.cycClassify := st.cycClassify + 1.U
      advance()
      when(passDone) { state := S.prefix; sent := false.B }
    }
    is(S.prefix) {
      st.cycPrefix := st.cycPrefix + 1.U
      sent := true.B
      when(sent && !sortBusy) { state := S.scatter; restart() }
    }
    is(S.scatter) {
      st.cycScatter := st.cycScatter + 1.U
      advance()
      // The last scatter write lands the cycle after its request: one cycle of margin.
      when(passDone && !RegNext(sortIns.map(_.fire).reduce(_ || _), false.B)) {
        state := S.generate; sent := false.B; scatterOver := true.B
      }
    }
    is(S.generate) {
      sent := true.B
      when(largeOnly) { st.cycLarge := st.cycLarge + 1.U }.otherwise {
        st.cycGrid := st.cycGrid + 1.U
        for ((_, c) <- GridCycle.names.zipWithIndex) {
          val lanesAt = gens.map(g => Mux(g.io.inGrid, g.io.gridCycle === c.U, (c == GridCycle.names.indexOf("done")).B))
          st.laneCycles(c) := st.laneCycles(c) + PopCount(lanesAt)
        }
      }
      when(sent && !gensBusy) {
        state := S.idle
        when(pending) { // the world begun ahead: its table is (being) fed, its counters clear now
          pending := false.B; handOver := true.B; setUp(pendingNum, pendingCuts, false.B); state := S.fill
        }
        st.level := level
        st.cells := laneSum(_.io.stats.cells); st.chunks := laneSum(_.io.stats.chunks)
        st.scanned := laneSum(_.io.stats.scanned); st.probes := laneSum(_.io.stats.probes)
        st.badBucket := sorts.map(_.io.badBucket).reduce(_ || _)
        st.sortMismatch := sorts.map(s => s.io.counted =/= s.io.scattered).reduce(_ || _)
      }
    }
  }
  io.status := st
}

object BroadPhase {
  /** Cycles of state box after the corners' keys come (box buckets): the box's map, an
    * operation a cycle (BroadPhase's box map). */
  val boxSteps: Int = 7
}
