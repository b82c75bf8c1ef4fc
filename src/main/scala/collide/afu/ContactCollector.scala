package collide.afu

import chisel3._
import chisel3.util._
import collide.scpu.{ContactKind, ScpuOut}

/** One slot as it goes into a line (docs/afu-interface.md, Contacts): a record (the
  * layout's value fields, then the tag word or, masked, the flags byte) or a mask header,
  * with the pair index the dense placement needs (for a header: its group's first pair). */
class ContactRecord(val lay: BufferLayout) extends Bundle {
  val bits = UInt(lay.recordBits.W)
  val pair = UInt(RecordTag.PAIR_BITS.W)
}
object ContactRecord {
  /** A record's bits as they lie in a line: field 0 at the lowest bits. */
  def pack(lay: BufferLayout, vals: Seq[UInt], pair: UInt, flags: UInt): UInt =
    if (lay.masked) Cat(flags, Cat(vals.reverse)) else Cat(flags, pair, Cat(vals.reverse))
  def header(lay: BufferLayout, first: UInt, mask: UInt): UInt =
    (Cat(0.U(MaskHeader.MASK_BITS.W) | mask, first.pad(MaskHeader.PAIR_BITS)) << MaskHeader.PAIR_SHIFT).pad(lay.recordBits) // (a Bool mask has no pad)
}

/** Takes the SCPUs' results back group by group, in dispatch order, and turns them into
  * records: every result in dense mode; in compact mode the hits and, with `keepFlagged` (pair
  * mode), the misses the arithmetic or a non-finite input flagged, so that no flag is lost
  * with its miss (docs/afu-interface.md, Contacts). Masked layouts in compact mode put a
  * group's mask header in the slot before its first record (`nHeaders`). It passes the packer
  * at most as many records a cycle as the packer has room for (`room`), and counts every pair
  * of a group when the group's last record has gone.
  *
  * Pipelined so that no stage holds more than a few levels of logic (docs/timing.md):
  *  - gather: a group is taken whole, when every SCPU it was dispatched to shows its result,
  *    into registers indexed by SCPU (the SCPUs a group used come from a register, so the
  *    decision is an AND over the SCPUs' valids);
  *  - order: the results rotated into the group's pair order, each made a record, and which
  *    of the group's slots (its header, then its pairs) write one;
  *  - count, in two stages: each slot's running count of records, by tables (ROMs, which map
  *    to LUTs) over groups of four slots and then over the groups, never a chain of carry cells
  *    (which the timing proxy showed the prefix sum becoming);
  *  - emit: up to `room` records a cycle. How many have gone is kept one-hot, so choosing the
  *    slot for each of the packer's places, how many fit and whether the group is done are
  *    AND-OR terms, not sums. The next group waits in a second register beside the one being
  *    emitted, so the stages before never wait on the emit's decision within a cycle.
  * A group a cycle goes through when its records fit the packer's room; the latency is five
  * cycles.
  */
class ContactCollector(p: PucParams) extends Module {
  override def desiredName = s"ContactCollector_n${p.scpus}${p.name}"
  private val n = p.scpus
  private val L = p.lanes
  private val R = p.layout.recordsPerLine
  private val E = L + 1 // slots: the mask header, then the group's L positions
  private val cntW = log2Ceil(L + 1)
  private val slotW = log2Ceil(E + 1)
  private val Q = 4     // slots a count table sees
  private val chunks = (0 until E).grouped(Q).toSeq
  require(L <= n, "a group uses each SCPU at most once")
  val io = IO(new Bundle {
    val dense  = Input(Bool())
    val keepFlagged = Input(Bool())
    val groups = Flipped(Decoupled(new GroupInfo(p)))
    val scpu   = Vec(n, Flipped(Decoupled(new ScpuOut(p.linkWidth, p.scpuTagBits))))
    val room   = Input(UInt(log2Ceil(R + 1).W))
    val recs   = Output(Vec(R, new ContactRecord(p.layout)))
    val nRecs  = Output(UInt(log2Ceil(R + 1).W))
    // per-cycle increments of the status counters
    val nPairs     = Output(UInt(cntW.W))
    val nHits      = Output(UInt(cntW.W))
    val nNonFinite = Output(UInt(cntW.W))
    val nFlagged   = Output(UInt(cntW.W)) // flagged misses (written in pair mode)
    val nHeaders   = Output(Bool())
  })
  private def arithOf(o: ScpuOut) = (o.flags & (collide.fp.FpFlags.Overflow | collide.fp.FpFlags.Invalid).U).orR
  private def table(in: UInt, w: Int)(f: Int => Int): UInt = collide.util.Table(in, w)(f)
  private def sumT(a: UInt, b: UInt): UInt =
    table(Cat(a, b), slotW)(v => math.min((v >> b.getWidth) + (v & ((1 << b.getWidth) - 1)), (1 << slotW) - 1))

  // ---- the group's SCPUs, from a register: (base + k) mod n for k < cnt
  val head = Module(new Queue(new GroupInfo(p), 2) {
    override def desiredName = s"CollectorGroupQueue_d2${p.name}"
  })
  head.io.enq <> io.groups
  val hg = head.io.deq.bits
  // (Tables here and below, not compares and sums: the proxy maps those to carry chains.)
  val used = VecInit.tabulate(n) { s =>
    table(Cat(hg.base, hg.cnt), 1) { v =>
      val (b, c) = (v >> hg.cnt.getWidth, v & ((1 << hg.cnt.getWidth) - 1))
      if (GroupInfo.position(n, b, s) < c) 1 else 0
    }.asBool
  }.asUInt

  // ---- gather: every result of the group at once, by SCPU
  class Gathered extends Bundle {
    val g   = new GroupInfo(p)
    val out = Vec(n, new ScpuOut(p.linkWidth, p.scpuTagBits))
  }
  val s1 = Reg(new Gathered)
  val s1Valid = RegInit(false.B)
  val s1Free = Wire(Bool())
  val allThere = (0 until n).map(s => !used(s) || io.scpu(s).valid).reduce(_ && _)
  val gather = head.io.deq.valid && allThere && s1Free
  head.io.deq.ready := gather
  for (s <- 0 until n) io.scpu(s).ready := gather && used(s)
  when(gather) {
    s1.g := hg
    for (s <- 0 until n) s1.out(s) := io.scpu(s).bits
  }

  // ---- order: pair order, records, and which slots write
  class Ordered extends Bundle {
    val cnt     = UInt(cntW.W)
    val rec     = Vec(E, UInt(p.layout.recordBits.W))
    val pair    = Vec(E, UInt(RecordTag.PAIR_BITS.W))
    val want    = Vec(E, Bool())
    val hitV    = Vec(L, Bool()) // counted by tables in the count stages, as the records are
    val nonFinV = Vec(L, Bool())
    val flagV   = Vec(L, Bool())
    val hits    = UInt(cntW.W)   // set by count, 2
    val nonFin  = UInt(cntW.W)
    val flagged = UInt(cntW.W)
  }
  val s2 = Reg(new Ordered)
  val s2Valid = RegInit(false.B)
  val s2Free = Wire(Bool())
  locally {
    val g = s1.g
    val at = VecInit.tabulate(L)(k => s1.out(table(g.base, log2Ceil(n).max(1))(b => (b + k) % n)))
    val active  = VecInit.tabulate(L)(k => table(g.cnt, 1)(c => if (k < c) 1 else 0).asBool)
    val inv     = VecInit.tabulate(L)(k => g.invalid(k))
    val hit     = VecInit.tabulate(L)(k => active(k) && !inv(k) && at(k).hit)
    val flagged = VecInit.tabulate(L)(k => active(k) && !inv(k) && !at(k).hit && (at(k).nonFinite || arithOf(at(k))))
    val nonFin  = VecInit.tabulate(L)(k => active(k) && !inv(k) && at(k).nonFinite)
    val record  = VecInit.tabulate(L)(k => hit(k) || (io.keepFlagged && flagged(k)))
    val want    = VecInit.tabulate(L)(k => active(k) && (io.dense || record(k)))
    val hdrMode = p.layout.masked.B && !io.dense
    val rec = VecInit.tabulate(L) { k =>
      val o = at(k)
      val fields: Map[String, UInt] = Map("px" -> o.px, "py" -> o.py, "pz" -> o.pz, "nx" -> o.nx, "ny" -> o.ny,
        "nz" -> o.nz, "depth" -> o.depth, "d" -> o.d, "w" -> o.nw)
      val pair = o.tag(RecordTag.PAIR_BITS - 1, 0)
      val flags = Mux(arithOf(o), RecordFlags.ARITH.U, 0.U) | Mux(o.nonFinite, RecordFlags.NONFINITE.U, 0.U) |
        (o.kind << RecordFlags.KIND_SHIFT) | Mux(o.hit, RecordFlags.HIT.U, 0.U)
      val zero = Seq.fill(p.layout.valueFields)(0.U(p.linkWidth.W))
      Mux(inv(k), ContactRecord.pack(p.layout, zero, pair, (ContactKind.Invalid << RecordFlags.KIND_SHIFT).U(8.W)),
        ContactRecord.pack(p.layout, p.layout.records.fields.map(fields), pair, flags.pad(8)))
    }
    when(s1Valid && s2Free) {
      s2.cnt := g.cnt
      s2.rec(0)  := ContactRecord.header(p.layout, g.first, VecInit.tabulate(L)(k => active(k) && record(k)).asUInt)
      s2.pair(0) := g.first
      s2.want(0) := hdrMode && record.zip(active).map { case (r, a) => r && a }.reduce(_ || _)
      for (k <- 0 until L) {
        s2.rec(k + 1)  := rec(k)
        s2.pair(k + 1) := at(k).tag(RecordTag.PAIR_BITS - 1, 0)
        s2.want(k + 1) := want(k)
      }
      s2.hitV    := hit
      s2.nonFinV := nonFin
      s2.flagV   := flagged
    }
  }

  // ---- count, 1: running counts within each group of Q slots, and each group's total
  val c1 = Reg(new Ordered)
  val c1Local = Reg(Vec(E, UInt(log2Ceil(Q + 1).W)))
  val c1Total = Reg(Vec(chunks.size, UInt(log2Ceil(Q + 1).W)))
  val c1Counts = Reg(Vec(3, Vec((L + Q - 1) / Q, UInt(log2Ceil(Q + 1).W)))) // hits, non-finite, flagged
  val c1Valid = RegInit(false.B)
  val c1Free = Wire(Bool())
  when(s2Valid && c1Free) {
    c1 := s2
    for ((v, i) <- Seq(s2.hitV, s2.nonFinV, s2.flagV).zipWithIndex; (ch, c) <- (0 until L).grouped(Q).zipWithIndex)
      c1Counts(i)(c) := table(Cat(ch.map(v(_)).reverse), log2Ceil(Q + 1))(Integer.bitCount)
    for ((ch, c) <- chunks.zipWithIndex) {
      val bits = Cat(ch.map(s2.want(_)).reverse)
      for ((e, i) <- ch.zipWithIndex) c1Local(e) := table(bits, log2Ceil(Q + 1))(v => Integer.bitCount(v & ((2 << i) - 1)))
      c1Total(c) := table(bits, log2Ceil(Q + 1))(Integer.bitCount)
    }
  }

  // ---- count, 2: each slot's running count over the whole group, one-hot, into `next`
  class Counted extends Bundle {
    val o      = new Ordered
    val cumOH  = Vec(E, UInt((E + 1).W))     // bit k: the slot's running count is k
    val totTh  = UInt((E + R + 2).W)          // bit k: k <= the group's records
  }
  val next = Reg(new Counted)
  val nextValid = RegInit(false.B)
  // Records before chunk c: its predecessors' totals summed as a balanced tree of tables.
  private def sumOf(ts: Seq[UInt]): UInt =
    if (ts.size == 1) ts.head else sumT(sumOf(ts.take(ts.size / 2)), sumOf(ts.drop(ts.size / 2)))
  val base = chunks.indices.map(c => if (c == 0) 0.U(slotW.W) else sumOf(c1Total.take(c)))
  val cum = VecInit.tabulate(E)(e => sumT(base(e / Q), c1Local(e)))
  val total = cum(E - 1)
  when(c1Valid && !nextValid) {
    next.o := c1
    next.o.hits    := sumOf(c1Counts(0))
    next.o.nonFin  := sumOf(c1Counts(1))
    next.o.flagged := sumOf(c1Counts(2))
    for (e <- 0 until E) next.cumOH(e) := UIntToOH(cum(e), E + 1)
    next.totTh := VecInit.tabulate(E + R + 2)(k => k.U <= total).asUInt
  }

  // ---- emit: from `cur`; `sent` one-hot (bit k: k records of cur have gone)
  val cur = Reg(new Counted)
  val curValid = RegInit(false.B)
  val sent = RegInit(1.U((E + 1).W))
  // Record sent + r + 1 exists (r = 0..R) ...
  val avail = VecInit.tabulate(R + 1)(r => (0 to E).map(j => sent(j) && cur.totTh(j + r + 1)).reduce(_ || _) && curValid)
  // ... and place r has room for it: a thermometer, from place 0
  val slotOk = VecInit.tabulate(R)(r => avail(r) && r.U < io.room)
  val takeOH = VecInit.tabulate(R + 1)(t => (if (t == 0) true.B else slotOk(t - 1)) && (if (t == R) true.B else !slotOk(t)))
  val done = curValid && (0 to R).map(t => takeOH(t) && !avail(t)).reduce(_ || _)
  for (r <- 0 until R) {
    val sel = (0 until E).map(e => cur.o.want(e) && (0 to E - r - 1).map(j => sent(j) && cur.cumOH(e)(j + r + 1)).foldLeft(false.B)(_ || _))
    io.recs(r).bits := Mux1H(sel, cur.o.rec)
    io.recs(r).pair := Mux1H(sel, cur.o.pair)
  }
  io.nRecs      := OHToUInt(takeOH)
  io.nPairs     := Mux(done, cur.o.cnt, 0.U)
  io.nHits      := Mux(done, cur.o.hits, 0.U)
  io.nNonFinite := Mux(done, cur.o.nonFin, 0.U)
  io.nFlagged   := Mux(done, cur.o.flagged, 0.U)
  io.nHeaders   := cur.o.want(0) && sent(0) && slotOk(0)
  val sentOn = VecInit.tabulate(E + 1)(j => (0 to math.min(R, j)).map(t => takeOH(t) && sent(j - t)).reduce(_ || _)).asUInt
  sent := Mux(done, 1.U, sentOn)

  // ---- the hand-over: `next` fills while empty, `cur` takes it as its group is done
  when(done || !curValid) {
    curValid := nextValid
    when(nextValid) { cur := next }
  }
  val nextTaken = nextValid && (done || !curValid)
  when(nextTaken) { nextValid := false.B }
  when(c1Valid && !nextValid) { nextValid := true.B }
  c1Free := !c1Valid || !nextValid
  s2Free := !s2Valid || c1Free
  s1Free := !s1Valid || s2Free
  when(c1Free) { c1Valid := s2Valid }
  when(s2Free) { s2Valid := s1Valid }
  when(s1Free) { s1Valid := gather }
}
