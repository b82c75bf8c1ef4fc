package collide.afu

import chisel3._
import chisel3.util._
import collide.scpu.{ScpuIn, ScpuOut}

/** The PUC: everything of the AFU but the SCPUs. CSRs, the run's state machine, the read
  * engine (sphere table then pair lines, reordered responses), the on-chip sphere table,
  * the dispatcher (a pair line's 16 pairs over N SCPUs), the collector and packer (records,
  * compact or dense), the write engine and the status line. With world mode built (MODE
  * bit 1), the broad phase reads the loaded table and its candidates replace the pair lines
  * (WorldPairLines); docs/afu.md describes both. With a run queue (two sphere tables), a start
  * during a run queues one more, and a queued world run's table loads into the other table
  * once the current run's is in (docs/afu.md, "The run queue").
  */
class Puc(p: PucParams) extends Module {
  override def desiredName = s"Puc${p.name}"
  private val lay = p.layout
  val io = IO(new Bundle {
    val link    = new LinkIO(p.tagBits)
    val scpuIn  = Vec(p.scpus, Decoupled(new ScpuIn(p.linkWidth, p.scpuTagBits)))
    val scpuOut = Vec(p.scpus, Flipped(Decoupled(new ScpuOut(p.linkWidth, p.scpuTagBits))))
    val busy    = Output(Bool())
    // Idle-waiting (docs/afu-interface.md, "Idle and skipping"): with no response and no CSR
    // arriving this cycle, the PUC drives no request and changes no state but its cycle
    // counters. Conservative: false whenever that is not certain.
    val idle       = Output(Bool())
    val skipCycles = Input(UInt(32.W)) // n > 0, only while idle: this edge counts as n cycles
    val dbg     = Output(Vec(8, UInt(32.W))) // for test diagnosis: see the end of this file
  })

  // ---- CSRs: take effect at once; a run works on the copy taken at its start.
  val csr = RegInit(VecInit(Seq.tabulate(Csr.count)(i =>
    (if (i == Csr.MODE && p.denseByDefault) 1 else 0).U(64.W))))
  val sIdle :: sCheck :: sRun :: sDrain :: sStatus :: sStatusWait :: Nil = Enum(6)
  val state = RegInit(sIdle)
  val startReq = io.link.csr.valid && io.link.csr.bits.index === Csr.CTRL.U && io.link.csr.bits.data === Csr.CTRL_START.U
  when(io.link.csr.valid && io.link.csr.bits.index =/= Csr.CTRL.U && io.link.csr.bits.index < Csr.count.U) {
    csr(io.link.csr.bits.index) := io.link.csr.bits.data
  }
  val run = Reg(Vec(Csr.count, UInt(64.W)))
  // The run queue: one run waits behind the current one (CSRs copied at its start, as a run's
  // are); `nextLoading` while the read engine loads its table into the table not being read.
  private val queued = p.tables > 1
  val next        = Reg(Vec(Csr.count, UInt(64.W)))
  val nextValid   = RegInit(false.B)
  val nextLoading = RegInit(false.B)
  val prefetched  = RegInit(false.B) // the current run's table was loaded while the one before it ran
  val curTable    = RegInit(0.U(1.W)) // the table the current run reads
  when(state === sIdle && startReq) { run := csr; state := sCheck; prefetched := false.B }
  val sphereBase = run(Csr.SPHERE_BASE); val numSpheres = run(Csr.NUM_SPHERES)
  val pairBase = run(Csr.PAIR_BASE); val numPairs64 = run(Csr.NUM_PAIRS)
  val contactBase = run(Csr.CONTACT_BASE); val capacity = run(Csr.CONTACT_CAPACITY)
  val statusAddr = run(Csr.STATUS_ADDR); val dense = run(Csr.MODE)(0)
  val numPairs = numPairs64(lay.pairIndexBits - 1, 0)
  val worldBit = run(Csr.MODE)(1)
  val world = worldBit && p.world.isDefined.B

  // ---- counters of the status line
  val errors     = RegInit(0.U(ErrorFlags.width.W))
  val processed  = RegInit(0.U(32.W))
  val found      = RegInit(0.U(32.W))
  val headers    = RegInit(0.U(32.W))   // masked compact: mask headers handed to the packer
  val nonFinite  = RegInit(0.U(32.W))
  val flaggedMiss = RegInit(0.U(32.W))  // misses with NONFINITE or ARITH (pair mode: records too)
  val records    = RegInit(0.U(35.W))   // compact: hits, flagged misses (pair mode) and headers
  val firstBad   = RegInit(StatusLine.NO_BAD_PAIR.U(32.W))
  val cycTotal   = RegInit(0.U(32.W))
  val cycLoad    = RegInit(0.U(32.W))
  val cycCompute = RegInit(0.U(32.W))
  val cycWaitRd  = RegInit(0.U(32.W))
  val cycWaitWr  = RegInit(0.U(32.W))

  // Cycles this edge stands for in every cycle counter: 1, or n when the host skips n idle cycles.
  val tick = Mux(io.skipCycles =/= 0.U, io.skipCycles, 1.U(32.W))

  /** A run's CSRs refused: (a bad configuration, more spheres than the table holds). */
  private def refusal(c: Vec[UInt]): (Bool, Bool) = {
    val wb = c(Csr.MODE)(1); val n = c(Csr.NUM_PAIRS)
    // x > bound as "a high bit set, or the low bits above it": a zero test and a short compare
    // rather than a 64-bit carry chain in front of the state register.
    def above(x: UInt, bound: BigInt): Bool = {
      val k = math.max(1, (bound + 1).bitLength)
      x(63, k).orR || x(k - 1, 0) > bound.U
    }
    // World mode ignores PAIR_BASE and NUM_PAIRS; it is refused where it is not built, and dense.
    val badPairs = !wb && (above(n, BigInt(lay.maxPairs) - 1) || (n =/= 0.U && c(Csr.PAIR_BASE) === 0.U))
    val badWorld = wb && (!p.world.isDefined.B || c(Csr.MODE)(0))
    val badConfig = badPairs || badWorld || (c(Csr.NUM_SPHERES) =/= 0.U && c(Csr.SPHERE_BASE) === 0.U) ||
      (c(Csr.CONTACT_CAPACITY) =/= 0.U && c(Csr.CONTACT_BASE) === 0.U) || c(Csr.STATUS_ADDR) === 0.U
    (badConfig, above(c(Csr.NUM_SPHERES), p.maxSpheres))
  }
  /** The run is over (its status written, or nowhere to write it): the queued run is next. */
  private val runEnds = WireDefault(false.B) // endRun() was called this cycle
  private def endRun(): Unit = {
    runEnds := true.B
    if (!queued) state := sIdle
    else when(nextValid) {
      run := next; nextValid := false.B; state := sCheck
      prefetched := nextLoading; nextLoading := false.B
      when(nextLoading) { curTable := ~curTable } // its table is the one just loaded
    }.otherwise { state := sIdle }
  }

  val runStart = WireDefault(false.B) // a run passed its checks: its counters and engines restart
  val loadStart = runStart && !prefetched // ... and its table is still to be read
  when(state === sCheck) {
    val (badConfig, tooMany) = refusal(run)
    errors := Mux(badConfig, ErrorFlags.BAD_CONFIG.U, 0.U) | Mux(tooMany, ErrorFlags.TOO_MANY_SPHERES.U, 0.U)
    when(badConfig && statusAddr === 0.U) {
      endRun() // nowhere to report: write nothing at all
    }.elsewhen(badConfig || tooMany) {
      state := sStatus
    }.otherwise {
      runStart := true.B; state := sRun
    }
  }
  val running = state === sRun || state === sDrain

  // ---- blocks
  val rd     = Module(new ReadEngine(p))
  val ram    = Module(new SphereRam(p))
  val disp   = Module(new PairDispatcher(p))
  val groups = Module(new Queue(new GroupInfo(p), p.groupsInFlight) {
    override def desiredName = s"GroupQueue_d${p.groupsInFlight}${p.name}"
  })
  val coll   = Module(new ContactCollector(p))
  val pack   = Module(new ContactPacker(p))
  val wr     = Module(new WriteEngine(p))

  val prefetchGo = WireDefault(false.B) // the read engine turns to the queued run's table
  // The broad phase takes a world begun ahead now (or never takes one: its table is read then).
  val bpTakesAhead = WireDefault(true.B)
  val bpQuiet = WireDefault(true.B) // the broad phase clears nothing and holds no fed sphere
  rd.io.start       := loadStart || prefetchGo
  rd.io.active      := running || nextLoading
  // The next run's from the cycle its table's load starts (the engine takes them at its start).
  // NUM_SPHERES is within the table whenever a read starts (refused runs read nothing), so
  // only its low bits are summed.
  // (Summed before the choice, so the late prefetchGo passes one multiplexer only.)
  val loadingNext = nextLoading || prefetchGo
  def sphereLines(n: UInt) = ((n(log2Ceil(p.maxSpheres + 1) - 1, 0) +& (lay.spheresPerLine - 1).U) >> log2Ceil(lay.spheresPerLine))(p.sphereLineBits, 0)
  rd.io.sphereBase  := Mux(loadingNext, next(Csr.SPHERE_BASE), sphereBase)
  rd.io.sphereLines := Mux(loadingNext, sphereLines(next(Csr.NUM_SPHERES)), sphereLines(numSpheres))
  rd.io.pairBase    := pairBase
  rd.io.pairLines   := Mux(world || loadingNext, 0.U, ((numPairs +& (lay.pairsPerLine - 1).U) >> log2Ceil(lay.pairsPerLine))(p.pairLineBits, 0))
  io.link.rdReq <> rd.io.rdReq
  rd.io.rdResp := io.link.rdResp
  ram.io.write  := rd.io.sphereWrite
  ram.io.wtable := Mux(nextLoading, ~curTable, curTable)
  ram.io.rtable := curTable
  ram.io.worldTable := curTable

  // The current run's table is in; latched, as the read engine may move on to the next run's.
  val tableIn = RegInit(false.B)
  val loaded = running && (tableIn || (rd.io.loaded && !nextLoading))
  when(loaded) { tableIn := true.B }
  when(state === sCheck) { tableIn := false.B }
  if (queued) {
    // Load the queued run's table once the current world run's is in and no read is in flight
    // (world mode reads nothing else), where the queued run is a world run that will not be refused.
    val (nextBad, nextTooMany) = refusal(next)
    prefetchGo := nextValid && !nextLoading && next(Csr.MODE)(1) && !nextBad && !nextTooMany &&
      world && loaded && rd.io.outstanding === 0.U && bpTakesAhead
    when(prefetchGo) { nextLoading := true.B }
  }

  // ---- world mode: the broad phase starts once the table is loaded; its candidates, in
  // lines, take the pair lines' place at the dispatcher.
  val bpStarted = RegInit(false.B)
  /** startAhead: the queued world run's broad phase is started, ahead of its run (its candidates
    * wait for it); at that run's check it is the run's own, already started. */
  val aheadStarted = RegInit(false.B)
  val aheadGo = WireDefault(false.B)
  val bpStart = world && loaded && !bpStarted
  when(bpStart) { bpStarted := true.B }
  when(aheadGo) { aheadStarted := true.B }
  when(state === sCheck) { bpStarted := aheadStarted; aheadStarted := false.B }
  val worldLine    = Wire(Decoupled(new PairLine(p.pairLineBits)))
  val worldEmitted = WireDefault(0.U((lay.pairIndexBits + 1).W)) // candidates handed to the dispatcher
  val worldDone    = WireDefault(false.B) // the broad phase is over and every candidate handed on
  val cycBroad = WireDefault(0.U(32.W)); val cellLevel = WireDefault(0.U(32.W))
  val largeSpheres = WireDefault(0.U(32.W)); val worldCheck = WireDefault(false.B)
  p.world match {
    case Some(w) =>
      // The table's lines feed the broad phase as they are written, a line's spheres a cycle
      // (its level is chosen meanwhile, so its first pass over the table is not run), where it has
      // a lane for each sphere of a line.
      val spl = lay.spheresPerLine
      val feedWidth = if (w.bp.lanes >= spl) spl else 0
      val bp = Module(new collide.world.BroadPhase(w.fp, w.bp, p.maxSpheres, feedWidth = feedWidth))
      // A queued world run's table is fed too, begun ahead once the current run's broad phase
      // is past its level and box (bpTakesAhead holds the prefetch until then); its counters are
      // cleared when the current run's broad phase is over, so its own first pass is not run.
      bp.io.begin := (loadStart && world) || prefetchGo // ignored without feed ports
      bpTakesAhead := !bp.beginsAhead.B || bp.io.canBegin
      bpQuiet := bp.io.quiet
      bp.io.start := bpStart || aheadGo
      // <= maxSpheres: checked at sCheck, and for the queued run before its prefetch
      bp.io.num   := Mux(prefetchGo || aheadGo, next(Csr.NUM_SPHERES), numSpheres)(bp.io.countW - 1, 0)
      val wr = rd.io.sphereWrite
      val feedNum = Mux(nextLoading, next(Csr.NUM_SPHERES), numSpheres)
      for ((f, s) <- bp.io.feed.zipWithIndex) {
        // Every world run's table, the current run's or the queued run's, however late its
        // lines come (a queued table may still be arriving when its run becomes current); the
        // broad phase ignores lines of a world whose begin it did not take.
        f.valid := wr.valid && (world || nextLoading) &&
          ((wr.bits.line << log2Ceil(spl)) +& s.U) < feedNum(log2Ceil(p.maxSpheres + 1) - 1, 0) // <= maxSpheres
        f.bits := Sphere.at(wr.bits.data, s * 4 * p.linkWidth, p.linkWidth).fields
      }
      for ((port, lane) <- ram.io.world.get.zip(bp.io.sphere)) {
        port.addr := lane.addr
        lane.data := port.data.fields
      }
      val lines = Module(new WorldPairLines(p, bp.io.itemW, w.bp.lanes, w.lineQueue))
      lines.io.start := runStart
      // A broad phase started ahead holds its candidates until its run is the current one.
      for ((in, out) <- lines.io.in.zip(bp.io.pairs)) {
        in.valid := out.valid && !aheadStarted
        in.bits := out.bits
        out.ready := in.ready && !aheadStarted
      }
      // This run's broad phase is over; latched, as with startAhead it may go on to the queued world.
      val bpOver = RegInit(false.B)
      val bpDoneNow = bpStarted && !bp.io.busy && !aheadStarted
      when(bpDoneNow) { bpOver := true.B }
      when(state === sCheck) { bpOver := false.B }
      val bpDone = bpOver || bpDoneNow
      lines.io.done := bpDone
      worldLine <> lines.io.out
      worldEmitted := lines.io.emitted
      worldDone := bpDone && lines.io.idle
      val st = bp.io.status
      class BroadStatus extends Bundle { val cyc = UInt(32.W); val level = UInt(32.W); val large = UInt(32.W); val check = Bool() }
      val now = Wire(new BroadStatus)
      now.cyc := st.cycTotal; now.level := st.level.pad(32).asUInt; now.large := st.large.pad(32)
      now.check := st.tooMany || st.cellOverflow || st.largeOverflow || st.badBucket || st.sortMismatch
      val shown = if (w.startAhead) {
        // Start the queued world once this run's broad phase is over and the queued table is in;
        // the broad phase's copies then read that table while the SCPUs finish this run's.
        aheadGo := world && nextLoading && rd.io.loaded && bpDone && !aheadStarted
        val bpTable = RegInit(0.U(1.W))
        when(aheadGo) { bpTable := ~curTable }.elsewhen(bpStart) { bpTable := curTable }
        ram.io.worldTable := bpTable
        // This run's broad-phase status, kept once the queued world's start clears it.
        Mux(aheadStarted, RegEnable(now, !aheadStarted), now)
      } else now
      cycBroad := shown.cyc; cellLevel := shown.level; largeSpheres := shown.large; worldCheck := shown.check
    case None =>
      worldLine.valid := false.B; worldLine.bits := DontCare
  }
  val worldActive = world && (bpStart || (bpStarted && !worldDone))

  disp.io.go         := loaded
  disp.io.numPairs   := Mux(world, worldEmitted(lay.pairIndexBits - 1, 0), numPairs)
  disp.io.numSpheres := numSpheres(16, 0)
  disp.io.world      := world
  disp.io.pairs.valid := Mux(world, worldLine.valid, rd.io.pairs.valid)
  disp.io.pairs.bits  := Mux(world, worldLine.bits, rd.io.pairs.bits)
  rd.io.pairs.ready   := !world && disp.io.pairs.ready
  worldLine.ready     := world && disp.io.pairs.ready
  ram.io.raddr := disp.io.raddr
  ram.io.ren   := disp.io.ren
  for (a <- ram.io.rport; b <- disp.io.rport) a := b
  disp.io.rdata := ram.io.rdata
  io.scpuIn <> disp.io.scpu
  groups.io.enq <> disp.io.groups

  coll.io.dense := dense
  coll.io.keepFlagged := !world // world mode writes contacts only (docs/afu.md, world mode)
  coll.io.groups <> groups.io.deq
  coll.io.scpu <> io.scpuOut
  coll.io.room := pack.io.room

  pack.io.start    := runStart
  pack.io.dense    := dense
  pack.io.numPairs := numPairs
  pack.io.base     := contactBase
  pack.io.capacity := capacity
  pack.io.recs     := coll.io.recs
  pack.io.nRecs    := coll.io.nRecs
  pack.io.flush    := state === sDrain
  wr.io.lines <> pack.io.lines
  wr.io.wrResp := io.link.wrResp
  io.link.wrReq <> wr.io.wrReq

  // ---- first pair with an out-of-range index: the lowest such pair index seen
  // In three steps (the group's bits, its lowest bad index, the compare), off the dispatcher's
  // path; its pairs take the SCPUs' whole latency to reach the status, so it is in time.
  locally {
    val enq  = groups.io.enq
    val bad1 = RegNext(enq.fire && enq.bits.invalid.orR, false.B)
    val grp1 = RegEnable(enq.bits, enq.fire)
    val bad2 = RegNext(bad1, false.B)
    val idx2 = RegNext(grp1.first + PriorityEncoder(grp1.invalid))
    when(bad2 && idx2 < firstBad) { firstBad := idx2 }
  }

  // ---- counting
  processed := processed + coll.io.nPairs
  found     := found + coll.io.nHits
  headers   := headers + coll.io.nHeaders
  nonFinite := nonFinite + coll.io.nNonFinite
  flaggedMiss := flaggedMiss + coll.io.nFlagged
  // Records of a compact run, counted as they come rather than summed from the counters at the
  // status: that sum and its compare with the capacity were the PUC's slowest path.
  records := records + (coll.io.nHits +& Mux(world, 0.U, coll.io.nFlagged) +& coll.io.nHeaders) // one wide adder
  when(running) {
    cycTotal := cycTotal + tick
    when(!loaded) { cycLoad := cycLoad + tick }
    when(disp.io.fired) { cycCompute := cycCompute + 1.U } // never idle: a group fired
    when(!disp.io.fired && !nextLoading && rd.io.outstanding =/= 0.U && (!loaded || (disp.io.idle && rd.io.pairBufferEmpty))) {
      cycWaitRd := cycWaitRd + tick
    }
    when(wr.io.blocked || (state === sDrain && wr.io.outstanding =/= 0.U)) { cycWaitWr := cycWaitWr + tick }
  }

  // Pairs handed to the dispatcher's RAM read, the SCPU queues and pipelines, or waiting in
  // the collector: zero means no result can still appear without a new pair line.
  val pairsInFlight = RegInit(0.U((lay.pairIndexBits + 1).W))
  pairsInFlight := pairsInFlight + Mux(disp.io.fired, groups.io.enq.bits.cnt, 0.U) - coll.io.nPairs

  when(state === sCheck) { // a new run: after the counting above, so these win
    processed := 0.U; found := 0.U; headers := 0.U; nonFinite := 0.U; flaggedMiss := 0.U; records := 0.U
    firstBad := StatusLine.NO_BAD_PAIR.U
    cycTotal := 1.U; cycLoad := 0.U; cycCompute := 0.U; cycWaitRd := 0.U; cycWaitWr := 0.U
  }

  val runDone   = Mux(world, worldDone && processed === worldEmitted, processed === numPairs) &&
    loaded && (nextLoading || rd.io.outstanding === 0.U) // reads in flight for the queued run are its own
  val drainDone = pack.io.idle && !wr.io.lines.valid && wr.io.outstanding === 0.U
  when(state === sRun && runDone) { state := sDrain }
  when(state === sDrain && drainDone) { state := sStatus }

  // ---- the status line
  val totalRecords = Mux(dense, numPairs.pad(records.getWidth), records) // slots, headers included
  // The capacity's bits above the records' width, tested a cycle ahead: it is a run register,
  // and the status comes at least a cycle after the run's check.
  val capHigh      = RegNext(capacity(63, records.getWidth) =/= 0.U)
  val overCap      = !capHigh && totalRecords > capacity(records.getWidth - 1, 0)
  val written      = Mux(overCap, capacity, totalRecords)(31, 0)
  val nothingRun   = (errors & (ErrorFlags.TOO_MANY_SPHERES | ErrorFlags.BAD_CONFIG).U).orR
  val capErr       = overCap && !nothingRun
  val errFlags     = errors | Mux(nonFinite =/= 0.U, ErrorFlags.NONFINITE.U, 0.U) | Mux(capErr, ErrorFlags.CAPACITY.U, 0.U) |
    Mux(firstBad =/= StatusLine.NO_BAD_PAIR.U, ErrorFlags.INDEX_RANGE.U, 0.U) |
    Mux(world && worldCheck && !nothingRun, ErrorFlags.WORLD_CHECK.U, 0.U)
  val words = WireInit(VecInit(Seq.fill(StatusLine.fields)(0.U(32.W))))
  words(StatusLine.DONE / 4)            := 1.U
  words(StatusLine.ERROR_FLAGS / 4)     := errFlags
  words(StatusLine.PAIRS_PROCESSED / 4) := processed
  words(StatusLine.CONTACTS_FOUND / 4)  := found
  words(StatusLine.RECORDS_WRITTEN / 4) := Mux(nothingRun, 0.U, written)
  words(StatusLine.NONFINITE_PAIRS / 4) := nonFinite
  words(StatusLine.FIRST_BAD_PAIR / 4)  := firstBad
  words(StatusLine.FLAGGED_MISSES / 4)  := flaggedMiss
  words(StatusLine.CYCLES_TOTAL / 4)    := cycTotal
  words(StatusLine.CYCLES_LOAD / 4)     := cycLoad
  words(StatusLine.CYCLES_COMPUTE / 4)  := cycCompute
  words(StatusLine.CYCLES_WAIT_RD / 4)  := cycWaitRd
  words(StatusLine.CYCLES_WAIT_WR / 4)  := cycWaitWr
  words(StatusLine.CYCLES_BROAD / 4)    := Mux(world && !nothingRun, cycBroad, 0.U)
  words(StatusLine.WORLD_CELL_LEVEL / 4) := Mux(world && !nothingRun, cellLevel, 0.U)
  words(StatusLine.WORLD_LARGE / 4)     := Mux(world && !nothingRun, largeSpheres, 0.U)
  wr.io.status.valid     := state === sStatus
  wr.io.status.bits.addr := statusAddr
  wr.io.status.bits.data := words.asUInt
  when(wr.io.status.fire) { state := sStatusWait }
  when(state === sStatus && !wr.io.status.fire) { cycTotal := cycTotal + tick }
  when(state === sStatusWait && wr.io.outstanding === 0.U) { endRun() }
  if (queued) {
    // A start during a run queues it, if the queue is free or moves on in this cycle (written
    // after endRun, so that its clear does not lose this start). A start with a run queued is
    // ignored, as a start during a run is without a queue (the host waits for a status first).
    when(startReq && state =/= sIdle && (!nextValid || runEnds)) { next := csr; nextValid := true.B }
  }
  io.busy := state =/= sIdle

  // Idle: no request goes out, and nothing inside can move without an input. In a run that
  // means no group fires, no pair line is taken, no pair is in flight (so the SCPUs and the
  // collector hold nothing valid and no record reaches the packer), and the state machine
  // waits on a response (sRun, sDrain: packer empty; sStatus: no free write tag; sStatusWait).
  val noRequest = !io.link.rdReq.valid && !io.link.wrReq.valid
  val quietRun  = !disp.io.fired && !disp.io.advance && !rd.io.pairs.fire && pairsInFlight === 0.U && !worldActive
  io.idle := noRequest && !prefetchGo && !aheadGo && bpQuiet && MuxLookup(state, false.B)(Seq(
    sIdle       -> true.B,
    sRun        -> (quietRun && !runDone),
    sDrain      -> (quietRun && pack.io.idle && !drainDone),
    sStatus     -> true.B,
    sStatusWait -> (wr.io.outstanding =/= 0.U)
  ))
  assert(io.skipCycles === 0.U || io.idle, "Puc: skipCycles given while not idle")
  io.dbg := VecInit(Seq(state.asUInt.pad(32), processed, rd.io.outstanding.pad(32), Cat(loaded, disp.io.idle, rd.io.pairBufferEmpty, pack.io.idle, wr.io.lines.valid),
    rd.io.dbg, wr.io.outstanding.pad(32), found, numPairs.pad(32)))
}
