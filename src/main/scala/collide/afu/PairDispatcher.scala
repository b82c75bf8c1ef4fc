package collide.afu

import chisel3._
import chisel3.util._
import collide.scpu.ScpuIn

/** One dispatched group: pairs `first .. first+cnt-1` of one pair line went to SCPUs
  * `(base + k) mod N`, k < cnt. `invalid(k)`: pair k had a sphere index out of range (its
  * SCPU computed on don't-care data; the collector replaces the result). The collector
  * takes results group by group in this order, so dense records come out in pair order
  * within a line. */
class GroupInfo(p: PucParams) extends Bundle {
  val base    = UInt(math.max(log2Ceil(p.scpus), 1).W)
  val cnt     = UInt(log2Ceil(p.lanes + 1).W)
  val invalid = UInt(p.lanes.W)
  val first   = UInt(p.layout.pairIndexBits.W)
}

/** Takes pair lines (any order), cuts each into groups of up to min(N, 16) consecutive pairs,
  * reads both spheres of every pair from the table and hands the pair to an SCPU. A group
  * fires when every SCPU it needs has room in its input queue, so a full line goes out per
  * cycle at N = 16 and N pairs per cycle for N dividing 16. SCPUs are used round robin, so
  * N > 16 spreads the work over all units. Nothing is dispatched before `go` (table loaded).
  * In world mode (`world`) a pair's tag, which becomes its record's pair field, names its
  * spheres (i | j << 12, RecordTag.WORLD_INDEX_BITS) instead of its place in the list.
  */
class PairDispatcher(p: PucParams) extends Module {
  override def desiredName = s"PairDispatcher_n${p.scpus}${p.name}"
  private val n = p.scpus
  private val ppl = p.layout.pairsPerLine
  private val idxBits = log2Ceil(p.maxSpheres)
  private val baseBits = math.max(log2Ceil(n), 1)
  val io = IO(new Bundle {
    val go         = Input(Bool())
    val numPairs   = Input(UInt(p.layout.pairIndexBits.W))
    val numSpheres = Input(UInt(17.W))
    val pairs      = Flipped(Decoupled(new PairLine(p.pairLineBits)))
    val raddr      = Output(Vec(n, Vec(2, UInt(idxBits.W))))
    val ren        = Output(Vec(n, Bool()))
    val rdata      = Input(Vec(n, Vec(2, new Sphere(p.linkWidth))))
    val rport      = if (p.banked) Some(Output(Vec(n, Vec(2, UInt(1.W))))) else None
    val scpu       = Vec(n, Decoupled(new ScpuIn(p.linkWidth, p.scpuTagBits)))
    val groups     = Decoupled(new GroupInfo(p))
    val fired      = Output(Bool())  // a group went out this cycle (the "computing" counter)
    val idle       = Output(Bool())  // no line held
    val advance    = Output(Bool())  // a waiting line moves up this cycle (not idle: skipping would miss it)
    val world      = Input(Bool())
  })

  private def table(in: UInt, w: Int)(f: Int => Int): UInt = collide.util.Table(in, w)(f)
  private val ptrW = log2Ceil(ppl + 1)
  private val cntW = log2Ceil(p.lanes + 1)
  private def pairI(line: UInt, k: Int) = line(32 * k + 15, 32 * k)
  private def pairJ(line: UInt, k: Int) = line(32 * k + 31, 32 * k + 16)

  // ---- a line waits one cycle in `nxt`: its pair count and its pairs' range checks are
  // registered there, so the per-group logic below starts from registers. (In world mode
  // numPairs grows, but only by lines after this one: a line's count is final once it is out.)
  val nxt      = Reg(new PairLine(p.pairLineBits))
  val nxtValid = RegInit(false.B)
  val nxtCount = Reg(UInt(ptrW.W))
  val nxtBad   = Reg(Vec(ppl, Bool()))
  locally {
    val first = (io.pairs.bits.line << log2Ceil(ppl)).asUInt.pad(p.layout.pairIndexBits + 1)
    val left  = io.numPairs.pad(p.layout.pairIndexBits + 1) - first
    when(io.pairs.fire) {
      nxt := io.pairs.bits
      nxtCount := Mux(left > ppl.U, ppl.U, left(ptrW - 1, 0))
      for (k <- 0 until ppl)
        nxtBad(k) := pairI(io.pairs.bits.data, k) >= io.numSpheres || pairJ(io.pairs.bits.data, k) >= io.numSpheres
    }
  }

  // ---- the line being dispatched: `rem` pairs left from slot `ptr`, the group's first pair
  // index `first`; SCPUs round robin from `base`
  val cur      = Reg(new PairLine(p.pairLineBits))
  val curBad   = Reg(Vec(ppl, Bool()))
  val curValid = RegInit(false.B)
  val ptr      = RegInit(0.U(ptrW.W))
  val rem      = RegInit(0.U(ptrW.W))
  val first    = Reg(UInt(p.layout.pairIndexBits.W))
  val base     = RegInit(0.U(baseBits.W))

  val lineCnt = table(rem, cntW)(r => math.min(r, p.lanes))
  val pi = VecInit.tabulate(ppl)(k => pairI(cur.data, k))
  val pj = VecInit.tabulate(ppl)(k => pairJ(cur.data, k))
  // Position k of the group: slot ptr + k of the line.
  val slot = VecInit.tabulate(p.lanes)(k => table(ptr, log2Ceil(ppl).max(1))(v => (v + k) % ppl))
  val posI = VecInit.tabulate(p.lanes)(k => pi(slot(k)))
  val posJ = VecInit.tabulate(p.lanes)(k => pj(slot(k)))

  // Banked sphere table: reads of one sphere share a port. Read r takes the port of its sphere
  // in its bank: 0 for the bank's first sphere in the group, 1 for its second. The group ends
  // before the first position that would give a bank a third sphere (position 0 always fits,
  // so every cycle makes progress). A list that names one sphere in consecutive pairs, as
  // ODE's do, so costs that sphere one read.
  val (cnt, ports) = p.ramPorts match {
    case SphereRamPorts.Replicated => (lineCnt, None)
    case _: SphereRamPorts.Banked =>
      val addr = (0 until p.lanes).flatMap(k => Seq(posI(k), posJ(k))).map(_(idxBits - 1, 0))
      val bank = addr.map(SphereRam.bankOf(p, _))
      val reads = addr.indices
      // For q < r: same(r)(q), read q is of r's sphere; sameBank(r)(q); seen(r)(q), a read at or
      // before q is of r's sphere.
      val same = reads.map(r => (0 until r).map(q => addr(q) === addr(r)))
      val sameBank = reads.map(r => (0 until r).map(q => bank(q) === bank(r)))
      val seen = reads.map(r => same(r).scanLeft(false.B)(_ || _).tail)
      // First read of its sphere in the group.
      val leader = reads.map(r => if (r == 0) true.B else !seen(r)(r - 1))
      // A sphere gets port 1 when another sphere of its bank came before its first read:
      // some q < r of its bank with no read of r's sphere at or before q.
      val port = reads.map { r =>
        if (r == 0) false.B else (0 until r).map(q => sameBank(r)(q) && !seen(r)(q)).reduce(_ || _)
      }
      // A bank's third sphere: a first read with two earlier first reads of its bank.
      val third = reads.map { r =>
        if (r < 2) false.B else leader(r) && PopCount((0 until r).map(q => leader(q) && sameBank(r)(q))) >= 2.U
      }
      val fits = (0 until p.lanes).map(k => !third(2 * k) && !third(2 * k + 1))
      val fitLen = PriorityEncoder(fits.map(!_) :+ true.B)
      (Mux(fitLen < lineCnt, fitLen, lineCnt)(cntW - 1, 0), Some(VecInit(port)))
  }
  val inGroupK = VecInit.tabulate(p.lanes)(k => table(cnt, 1)(c => if (k < c) 1 else 0).asBool)

  // Per SCPU: its position in the group, and whether it has one (tables on the registers).
  val posOf = VecInit.tabulate(n)(s => table(base, log2Ceil(n).max(1))(b => GroupInfo.position(n, b, s)))
  val inGroup = VecInit.tabulate(n) { s =>
    if (p.banked) posOf(s) < cnt
    else table(Cat(base, rem), 1) { v =>
      val (b, r) = (v >> ptrW, v & ((1 << ptrW) - 1))
      if (GroupInfo.position(n, b, s) < math.min(r, p.lanes)) 1 else 0
    }.asBool
  }

  // Input queue per SCPU; `held` counts its entries and the RAM read in flight to it.
  val inflight = RegInit(VecInit(Seq.fill(n)(false.B)))
  val queues = Seq.tabulate(n) { s =>
    Module(new Queue(new ScpuIn(p.linkWidth, p.scpuTagBits), p.scpuQueueDepth) {
      override def desiredName = s"ScpuInQueue_d${p.scpuQueueDepth}_w${p.linkWidth}${p.name}"
    })
  }
  private val heldW = log2Ceil(p.scpuQueueDepth + 1)
  val held = RegInit(VecInit(Seq.fill(n)(0.U(heldW.W))))
  val credit = VecInit.tabulate(n)(s => table(held(s), 1)(h => if (h < p.scpuQueueDepth) 1 else 0).asBool)

  val haveGroup = io.go && curValid && cnt =/= 0.U
  val ready = (0 until n).map(s => !inGroup(s) || credit(s)).reduce(_ && _)
  val fire = haveGroup && io.groups.ready && ready
  io.fired := fire
  io.idle  := !curValid && !nxtValid

  io.groups.valid        := haveGroup && ready
  io.groups.bits.base    := base
  io.groups.bits.cnt     := cnt
  io.groups.bits.invalid := VecInit.tabulate(p.lanes)(k => curBad(slot(k)) && inGroupK(k)).asUInt
  io.groups.bits.first   := first

  val tagNext = Reg(Vec(n, UInt(p.layout.pairIndexBits.W)))
  for (s <- 0 until n) {
    val k = posOf(s)(log2Ceil(p.lanes).max(1) - 1, 0)
    val kk = if (p.lanes == 1) 0.U else k
    io.ren(s)      := fire && inGroup(s)
    io.raddr(s)(0) := posI(kk)(idxBits - 1, 0)
    io.raddr(s)(1) := posJ(kk)(idxBits - 1, 0)
    for (pt <- ports; port <- 0 until 2) io.rport.get(s)(port) := pt(Cat(kk, port.U(1.W))).asUInt
    inflight(s)    := io.ren(s)
    val wb = RecordTag.WORLD_INDEX_BITS
    val worldTag = if (p.world.isDefined) Cat(posJ(kk)(wb - 1, 0), posI(kk)(wb - 1, 0)) else 0.U
    when(io.ren(s)) { tagNext(s) := Mux(io.world && p.world.isDefined.B, worldTag, first + kk) }
    val q = queues(s).io.enq
    q.valid := inflight(s)
    q.bits.x1 := io.rdata(s)(0).x; q.bits.y1 := io.rdata(s)(0).y; q.bits.z1 := io.rdata(s)(0).z; q.bits.r1 := io.rdata(s)(0).r
    q.bits.x2 := io.rdata(s)(1).x; q.bits.y2 := io.rdata(s)(1).y; q.bits.z2 := io.rdata(s)(1).z; q.bits.r2 := io.rdata(s)(1).r
    q.bits.tag := tagNext(s)
    assert(!q.valid || q.ready, "PairDispatcher: SCPU input queue overflow (credit broken)")
    io.scpu(s) <> queues(s).io.deq
    // (combinations that cannot happen, a take from nothing or a read past the depth, clamp)
    held(s) := table(Cat(held(s), io.ren(s), queues(s).io.deq.fire), heldW) { v =>
      ((v >> 2) + (v >> 1 & 1) - (v & 1)).max(0).min(p.scpuQueueDepth)
    }
  }

  val lineDone = fire && rem === cnt
  val takeNxt  = nxtValid && (!curValid || lineDone)
  when(fire) {
    ptr := ptr + cnt
    rem := rem - cnt
    first := first + cnt
    base := table(Cat(base, cnt), baseBits)(v => ((v >> cntW) + (v & ((1 << cntW) - 1))) % n)
  }
  when(takeNxt) {
    cur := nxt; curBad := nxtBad; curValid := true.B
    ptr := 0.U; rem := nxtCount; first := (nxt.line << log2Ceil(ppl)).asUInt
  }.elsewhen(lineDone) { curValid := false.B }
  io.advance := takeNxt
  io.pairs.ready := !nxtValid || takeNxt
  when(io.pairs.fire) { nxtValid := true.B }.elsewhen(takeNxt) { nxtValid := false.B }
}

object GroupInfo {
  /** Position of SCPU `s` in a group starting at SCPU `base` of `n`: (s - base) mod n. For the
    * tables that give the collector and the dispatcher a group's SCPUs. */
  def position(n: Int, base: Int, s: Int): Int = ((s - base) % n + n) % n
}
