package collide.world

import chisel3._
import chisel3.util._
import collide.fp.{FpParams, Pipeline}

/** What a world's run of the broad phase found and what it cost, valid once busy falls. */
class BroadPhaseStatus(kWidth: Int, countW: Int) extends Bundle {
  val k = SInt(kWidth.W)
  val excluded = UInt(countW.W)
  val large = UInt(countW.W)
  val small = UInt(countW.W)
  val candidates = UInt(32.W)
  val cells = UInt(32.W)
  val chunks = UInt(32.W)
  val scanned = UInt(32.W)
  val probes = UInt(32.W)
  /** Cycles per pass: the first table read (k), the second (classify and count), the
    * prefix sum, the scatter, the grid's candidate generation, the large pass, all. */
  val cycLoad, cycClassify, cycPrefix, cycScatter, cycGrid, cycLarge, cycTotal = UInt(32.W)
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
  * at the chosen k: small spheres counted into their bucket, large ones into the large list;
  * (3) the prefix sum; (4) the scatter, reading the spheres a third time; (5) the
  * CandidateGenerator, whose key records SphereKeys recomputes from the sphere table (no
  * key table: the table the AFU holds anyway is the only per-sphere RAM besides the sort's).
  * One sphere a cycle in each pass. The golden model is
  * BroadPhaseModel; the spec BroadPhaseSpec compares them pair for pair.
  */
class BroadPhaseIO(p: FpParams, bp: BroadPhaseParams, maxSpheres: Int) extends Bundle {
  val itemW = log2Ceil(maxSpheres)
  val countW = log2Ceil(maxSpheres + 1)
  val start = Input(Bool())
  val num = Input(UInt(countW.W))
  val sphere = new Bundle {
    val addr = Output(UInt(itemW.W))
    val data = Input(Vec(4, UInt(p.width.W))) // the cycle after
  }
  val pairs = Decoupled(new WorldPair(itemW))
  val busy = Output(Bool())
  val status = Output(new BroadPhaseStatus(SphereKeys.kWidth(p), countW))
}

class BroadPhase(p: FpParams, bp: BroadPhaseParams, maxSpheres: Int, keysLatency: Int = 1) extends Module {
  require(maxSpheres >= 2 && maxSpheres <= (1 << 24), s"maxSpheres must be 2..2^24, got $maxSpheres")
  /** Buckets the table holds: the model's cap, and no more than 2 maxSpheres can use. */
  val tableLog2: Int = bp.tableLog2(maxSpheres)
  private val largeSlots = math.max(1, bp.largeMax)
  override def desiredName =
    s"BroadPhase_${p.name}_n${maxSpheres}_b${tableLog2}_L${bp.largeMax}_k${bp.chunk}_c${bp.cellBits}_f${bp.filterFracBits}_w${bp.wordLog2}"
  val io = IO(new BroadPhaseIO(p, bp, maxSpheres))
  private val itemW = io.itemW
  private val countW = io.countW
  private val qWidth = SphereKeys.qWidth(bp)
  private val kWidth = SphereKeys.kWidth(p)

  private val keys = Module(new SphereKeys(p, bp, keysLatency))
  private val cellExp = Module(new CellExponent(p, bp))
  private val sort = Module(new BucketSort(maxSpheres, tableLog2, bp.wordLog2))
  private val gen = Module(new CandidateGenerator(itemW, countW, bp.cellBits, qWidth, tableLog2, bp.chunk, largeSlots,
    keyLatency = 1 + keysLatency, wordLog2 = math.min(bp.wordLog2, tableLog2)))
  private val larges = Reg(Vec(largeSlots, new WorldKey(itemW, bp.cellBits, qWidth)))

  private object S extends ChiselEnum { val idle, load, classify, prefix, scatter, generate = Value }
  private val state = RegInit(S.idle)
  io.busy := state =/= S.idle

  private val num = Reg(UInt(countW.W))
  private val usedLog2 = Reg(UInt(log2Ceil(tableLog2 + 1).W))
  private val i = Reg(UInt(countW.W))         // the next sphere (or key) to read
  private val inflight = RegInit(0.U(3.W))    // sphere reads not yet out of SphereKeys (0: ko.valid is low)
  private val sent = Reg(Bool())
  private val st = RegInit(0.U.asTypeOf(new BroadPhaseStatus(kWidth, countW)))
  private val largeCount = RegInit(0.U(log2Ceil(largeSlots + 1).W))

  /** log2 of BroadPhaseModel.bucketsFor(n): the least t with 2^t >= 2n, capped at the table. */
  private def bucketsLog2For(n: UInt): UInt = {
    val ceilLog2 = Mux(n <= 1.U, 0.U, Log2(n - 1.U) +& 1.U)
    val t = Mux(n === 0.U, 0.U, ceilLog2 +& 1.U)
    Mux(t > tableLog2.U, tableLog2.U, t)
  }

  // --- passes 1, 2 and 4: read the sphere table, one sphere a cycle, through SphereKeys -----
  // (in pass 5 the generator reads it, for its key records)
  private val reading = (state === S.load || state === S.classify || state === S.scatter) && i < num
  io.sphere.addr := Mux(state === S.generate, gen.io.keyAddr, i(itemW - 1, 0))
  private val rdValid = RegNext(reading, false.B)
  private val rdIndex = RegNext(i(itemW - 1, 0))
  keys.io.in.valid := rdValid
  keys.io.in.sphere := io.sphere.data
  keys.io.in.k := Mux(state === S.load, 0.S, cellExp.io.k) // need and top do not depend on k
  private val kIndex = Pipeline(rdIndex, keysLatency, true.B)
  private val ko = keys.io.out
  inflight := inflight + reading.asUInt - ko.valid.asUInt

  cellExp.io.clear := io.start && state === S.idle
  cellExp.io.in.valid := ko.valid && state === S.load
  cellExp.io.in.need := ko.need; cellExp.io.in.needNone := ko.needNone
  cellExp.io.in.top := ko.top; cellExp.io.in.topNone := ko.topNone
  cellExp.io.in.nonFinite := ko.nonFinite

  private val k = cellExp.io.k
  private val isLarge = !ko.nonFinite && !ko.needNone && ko.need > k
  private val isSmall = !ko.nonFinite && !isLarge
  private val classified = ko.valid && state === S.classify
  private val rec = Wire(new KeyRecord(bp.cellBits, qWidth))
  rec.cell := ko.cell; rec.q := ko.q; rec.qr := ko.qr; rec.large := isLarge; rec.excluded := ko.nonFinite
  gen.io.keyData := rec
  when(classified) {
    when(ko.nonFinite) { st.excluded := st.excluded + 1.U }
    when(isSmall) {
      st.small := st.small + 1.U
      when(ko.cellOverflow) { st.cellOverflow := true.B }
    }
    when(isLarge) {
      when(largeCount < bp.largeMax.U) {
        larges(VecIndex(largeCount, largeSlots)) := WorldKey(itemW, kIndex, rec)
        largeCount := largeCount + 1.U
        st.large := st.large + 1.U
      }.otherwise { st.largeOverflow := true.B }
    }
  }

  sort.io.usedLog2 := usedLog2
  sort.io.clear := io.start && state === S.idle
  sort.io.prefix := state === S.prefix && !sent
  private val scattered = ko.valid && state === S.scatter
  sort.io.in.valid := (classified || scattered) && isSmall
  sort.io.in.bits.scatter := state === S.scatter
  sort.io.in.bits.bucket := CellHash(ko.cell, tableLog2, usedLog2)
  sort.io.in.bits.item := kIndex
  assert(!sort.io.in.valid || sort.io.in.ready, "BroadPhase: the sort was not ready (a pass overlapped its clear or prefix)")
  sort.io.lookup.bucket := gen.io.lookup.bucket
  gen.io.lookup.begin := sort.io.lookup.begin; gen.io.lookup.end := sort.io.lookup.end
  gen.io.lookup.word := sort.io.lookup.word
  sort.io.entry.addr := gen.io.entry.addr
  gen.io.entry.item := sort.io.entry.item; gen.io.entry.mark := sort.io.entry.mark
  sort.io.mark := gen.io.mark

  gen.io.start := state === S.generate && !sent
  gen.io.usedLog2 := usedLog2
  gen.io.num := num
  gen.io.slack := {
    // BroadPhaseModel.boxSlack: 1 + max(1, 2^(errorExp + F - k)), saturated to the width.
    val e = bp.errorExp(p).S +& bp.filterFracBits.S -& k
    val big = e >= (qWidth - 1).S
    Mux(e < 0.S, 2.U, Mux(big, ((BigInt(1) << qWidth) - 1).U, 1.U +& (1.U << e.asUInt(log2Ceil(qWidth) - 1, 0))))
  }
  gen.io.larges := larges
  gen.io.largeCount := largeCount
  io.pairs <> gen.io.pairs
  when(io.pairs.fire) { st.candidates := st.candidates + 1.U }

  // --- sequencing ----------------------------------------------------------------------------
  when(state =/= S.idle) { st.cycTotal := st.cycTotal + 1.U }
  switch(state) {
    is(S.idle) {
      when(io.start) {
        val z = WireDefault(0.U.asTypeOf(st))
        num := io.num; usedLog2 := bucketsLog2For(io.num); i := 0.U; largeCount := 0.U
        when(io.num > maxSpheres.U) { z.tooMany := true.B; st := z }
          .otherwise { st := z; state := S.load }
      }
    }
    is(S.load) {
      st.cycLoad := st.cycLoad + 1.U
      when(reading) { i := i + 1.U }
      when(i === num && inflight === 0.U && !sort.io.busy) { state := S.classify; i := 0.U }
    }
    is(S.classify) {
      st.cycClassify := st.cycClassify + 1.U
      when(reading) { i := i + 1.U }
      when(i === num && inflight === 0.U) { state := S.prefix; sent := false.B }
    }
    is(S.prefix) {
      st.cycPrefix := st.cycPrefix + 1.U
      sent := true.B
      when(sent && !sort.io.busy) { state := S.scatter; i := 0.U }
    }
    is(S.scatter) {
      st.cycScatter := st.cycScatter + 1.U
      when(reading) { i := i + 1.U }
      // The last scatter write lands the cycle after its request: one cycle of margin.
      when(i === num && inflight === 0.U && !RegNext(sort.io.in.fire, false.B)) {
        state := S.generate; sent := false.B
      }
    }
    is(S.generate) {
      sent := true.B
      when(gen.io.inLargePass) { st.cycLarge := st.cycLarge + 1.U }.otherwise { st.cycGrid := st.cycGrid + 1.U }
      when(sent && !gen.io.busy) {
        state := S.idle
        st.k := k
        st.cells := gen.io.stats.cells; st.chunks := gen.io.stats.chunks
        st.scanned := gen.io.stats.scanned; st.probes := gen.io.stats.probes
        st.badBucket := sort.io.badBucket
        st.sortMismatch := sort.io.counted =/= sort.io.scattered
      }
    }
  }
  io.status := st
}
