package collide.afu

import chisel3._
import chisel3.util._
import collide.scpu.{ContactKind, ScpuOut}
import collide.util.Prefix

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
  *    positions write one;
  *  - count: each slot's running record count (a prefix sum, log2 levels);
  *  - emit: up to `room` records a cycle, the slot whose count is the next one going to each
  *    of the packer's places; the group leaves, and its pairs are counted, with its last record.
  * Each stage holds one group and passes it on as the next frees, so a group a cycle goes
  * through when its records fit the packer's room; the latency is four cycles.
  */
class ContactCollector(p: PucParams) extends Module {
  override def desiredName = s"ContactCollector_n${p.scpus}${p.name}"
  private val n = p.scpus
  private val L = p.lanes
  private val R = p.layout.recordsPerLine
  private val E = L + 1 // emit slots: the mask header, then the group's L positions
  private val cntW = log2Ceil(L + 1)
  private val slotW = log2Ceil(E + 1)
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

  // ---- the group's SCPUs, from a register: (base + k) mod n for k < cnt
  class Head extends Bundle {
    val g    = new GroupInfo(p)
    val used = UInt(n.W)
  }
  val head = Module(new Queue(new GroupInfo(p), 2) {
    override def desiredName = s"CollectorGroupQueue_d2${p.name}"
  })
  head.io.enq <> io.groups
  val hg = head.io.deq.bits
  val used = VecInit.tabulate(n) { s =>
    // SCPU s is position k = (s - base) mod n, used if k < cnt
    val k = Mux(s.U >= hg.base, s.U - hg.base, (s + n).U - hg.base)
    k < hg.cnt
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
    val g       = new GroupInfo(p)
    val rec     = Vec(E, UInt(p.layout.recordBits.W))
    val pair    = Vec(E, UInt(RecordTag.PAIR_BITS.W))
    val want    = Vec(E, Bool())
    val hits    = UInt(cntW.W)
    val nonFin  = UInt(cntW.W)
    val flagged = UInt(cntW.W)
  }
  val s2 = Reg(new Ordered)
  val s2Valid = RegInit(false.B)
  val s2Free = Wire(Bool())
  locally {
    val g = s1.g
    val at = VecInit.tabulate(L) { k =>
      val b = g.base +& k.U
      s1.out(Mux(b >= n.U, b - n.U, b))
    }
    val active  = VecInit.tabulate(L)(k => k.U < g.cnt)
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
      s2.g := g
      s2.rec(0)  := ContactRecord.header(p.layout, g.first, VecInit.tabulate(L)(k => active(k) && record(k)).asUInt)
      s2.pair(0) := g.first
      s2.want(0) := hdrMode && record.zip(active).map { case (r, a) => r && a }.reduce(_ || _)
      for (k <- 0 until L) {
        s2.rec(k + 1)  := rec(k)
        s2.pair(k + 1) := at(k).tag(RecordTag.PAIR_BITS - 1, 0)
        s2.want(k + 1) := want(k)
      }
      s2.hits    := PopCount(hit)
      s2.nonFin  := PopCount(nonFin)
      s2.flagged := PopCount(flagged)
    }
  }

  // ---- count: each slot's running count of records (inclusive)
  val s3 = Reg(new Ordered)
  val s3Cum = Reg(Vec(E, UInt(slotW.W)))
  val s3Valid = RegInit(false.B)
  val s3Free = Wire(Bool())
  when(s2Valid && s3Free) {
    s3 := s2
    s3Cum := VecInit(Prefix(s2.want.toSeq.map(w => Mux(w, 1.U(slotW.W), 0.U(slotW.W))))(_ + _))
  }

  // ---- emit: the next records, as many as the packer has room for
  val sent = RegInit(0.U(slotW.W)) // records of the s3 group already passed on
  val total = s3Cum(E - 1)
  val left = total - sent
  val take = Mux(s3Valid, Mux(left < io.room, left, io.room), 0.U)
  val done = s3Valid && sent + take === total
  for (r <- 0 until R) {
    val sel = (0 until E).map(e => s3.want(e) && s3Cum(e) === sent +& (r + 1).U)
    io.recs(r).bits := Mux1H(sel, s3.rec)
    io.recs(r).pair := Mux1H(sel, s3.pair)
  }
  io.nRecs      := take
  io.nPairs     := Mux(done, s3.g.cnt, 0.U)
  io.nHits      := Mux(done, s3.hits, 0.U)
  io.nNonFinite := Mux(done, s3.nonFin, 0.U)
  io.nFlagged   := Mux(done, s3.flagged, 0.U)
  io.nHeaders   := s3Valid && s3.want(0) && sent === 0.U && take =/= 0.U
  sent := Mux(done, 0.U, sent + take)

  // ---- the stages' hand-over: each takes the next group as it frees
  s3Free := !s3Valid || done
  s2Free := !s2Valid || s3Free
  s1Free := !s1Valid || s2Free
  when(s3Free) { s3Valid := s2Valid }
  when(s2Free) { s2Valid := s1Valid }
  when(s1Free) { s1Valid := gather }
}
