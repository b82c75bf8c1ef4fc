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
  * with its miss (docs/afu-interface.md, Contacts). It passes the packer at
  * most as many records a cycle as the packer has room for (`room`), and consumes every
  * result up to the last record taken (plus the misses after it in compact mode), so a line
  * of 16 pairs with at most two hits leaves in one cycle. Counts every pair it consumes.
  * Masked layouts in compact mode: a group with a record waits until all its results are there,
  * then its mask header goes first (in the slot before its first record, `nHeaders`).
  */
class ContactCollector(p: PucParams) extends Module {
  override def desiredName = s"ContactCollector_n${p.scpus}${p.name}"
  private val n = p.scpus
  private val L = p.lanes
  private val R = p.layout.recordsPerLine
  val io = IO(new Bundle {
    val dense  = Input(Bool())
    val keepFlagged = Input(Bool())
    val groups = Flipped(Decoupled(new GroupInfo(p)))
    val scpu   = Vec(n, Flipped(Decoupled(new ScpuOut(p.linkWidth, p.scpuTagBits))))
    val room   = Input(UInt(log2Ceil(R + 1).W))
    val recs   = Output(Vec(R, new ContactRecord(p.layout)))
    val nRecs  = Output(UInt(log2Ceil(R + 1).W))
    // per-cycle increments of the status counters
    val nPairs     = Output(UInt(log2Ceil(L + 1).W))
    val nHits      = Output(UInt(log2Ceil(L + 1).W))
    val nNonFinite = Output(UInt(log2Ceil(L + 1).W))
    val nFlagged   = Output(UInt(log2Ceil(L + 1).W)) // flagged misses (written in pair mode)
    val nHeaders   = Output(Bool())
  })

  val g  = io.groups.bits
  val sp = RegInit(0.U(log2Ceil(L + 1).W))

  val scpuAt = VecInit.tabulate(L) { k =>
    val b = g.base +& k.U
    Mux(b >= n.U, b - n.U, b)
  }
  val outAt   = VecInit.tabulate(L)(k => io.scpu(scpuAt(k)).bits)
  val validAt = VecInit.tabulate(L)(k => VecInit(io.scpu.map(_.valid))(scpuAt(k)))
  val active  = VecInit.tabulate(L)(k => io.groups.valid && k.U >= sp && k.U < g.cnt)
  val inv     = VecInit.tabulate(L)(k => g.invalid(k))
  val hit     = VecInit.tabulate(L)(k => !inv(k) && outAt(k).hit)
  private def arithOf(o: ScpuOut) = (o.flags & (collide.fp.FpFlags.Overflow | collide.fp.FpFlags.Invalid).U).orR
  val flagged = VecInit.tabulate(L)(k => !inv(k) && !outAt(k).hit && (outAt(k).nonFinite || arithOf(outAt(k))))
  val record  = VecInit.tabulate(L)(k => hit(k) || (io.keepFlagged && flagged(k))) // compact mode's records
  val want    = VecInit.tabulate(L)(k => active(k) && (io.dense || record(k)))

  // Masked compact: the header needs the whole group's hits, so nothing of a group with a
  // hit is taken before every result is there, and the header takes the first free slot.
  val hdrMode  = p.layout.masked.B && !io.dense
  val hdrSent  = RegInit(false.B)
  val allValid = (0 until L).map(k => !active(k) || validAt(k)).reduce(_ && _)
  val needHdr  = hdrMode && !hdrSent && (0 until L).map(k => active(k) && record(k)).reduce(_ || _)
  val hdrFire  = needHdr && allValid && io.room =/= 0.U
  val off      = needHdr.asUInt

  // Consume positions in order while their results are there and the records fit.
  // Both in log2(L) levels (Prefix): as a chain of L adders, the records' count was the
  // collector's slowest path (docs/afu.md, "Timing").
  val okPrefix  = VecInit(Prefix((0 until L).map(k => !active(k) || validAt(k)))(_ && _))
  val wantCount = VecInit(Prefix((0 until L).map(k => Mux(want(k), 1.U(log2Ceil(L + 1).W), 0.U)))(_ + _))
  val take      = VecInit.tabulate(L)(k => active(k) && okPrefix(k) && (!needHdr || allValid) && wantCount(k) +& off <= io.room)
  for (s <- 0 until n) {
    io.scpu(s).ready := (0 until L).map(k => take(k) && scpuAt(k) === s.U).foldLeft(false.B)(_ || _)
  }

  private def recordOf(k: Int): ContactRecord = {
    val o = outAt(k)
    val r = Wire(new ContactRecord(p.layout))
    val arith = arithOf(o)
    val fields: Map[String, UInt] = Map("px" -> o.px, "py" -> o.py, "pz" -> o.pz, "nx" -> o.nx, "ny" -> o.ny,
      "nz" -> o.nz, "depth" -> o.depth, "d" -> o.d, "w" -> o.nw)
    val pair = o.tag(RecordTag.PAIR_BITS - 1, 0)
    val flags = Mux(arith, RecordFlags.ARITH.U, 0.U) | Mux(o.nonFinite, RecordFlags.NONFINITE.U, 0.U) |
      (o.kind << RecordFlags.KIND_SHIFT) | Mux(o.hit, RecordFlags.HIT.U, 0.U)
    val zero = Seq.fill(p.layout.valueFields)(0.U(p.linkWidth.W))
    r.bits := Mux(inv(k), ContactRecord.pack(p.layout, zero, pair, (ContactKind.Invalid << RecordFlags.KIND_SHIFT).U(8.W)),
      ContactRecord.pack(p.layout, p.layout.records.fields.map(fields), pair, flags.pad(8)))
    r.pair := pair
    r
  }
  val records = VecInit.tabulate(L)(recordOf)
  val header  = Wire(new ContactRecord(p.layout))
  // Only positions not yet consumed: an SCPU whose result was taken already shows its next
  // result (another group's), and every consumed position of this group had no record (a
  // record holds the whole group until its header goes).
  header.bits := ContactRecord.header(p.layout, g.first, VecInit.tabulate(L)(k => active(k) && record(k)).asUInt)
  header.pair := g.first
  val nTaken  = PopCount(take)
  val nRecs   = PopCount((0 until L).map(k => take(k) && want(k))) +& hdrFire.asUInt
  for (r <- 0 until R) {
    val sel = (0 until L).map(k => take(k) && want(k) && (wantCount(k) +& off) === (r + 1).U)
    io.recs(r) := (if (r == 0) Mux(hdrFire, header, Mux1H(sel, records)) else Mux1H(sel, records))
  }
  io.nRecs      := nRecs
  io.nPairs     := nTaken
  io.nHits      := PopCount((0 until L).map(k => take(k) && hit(k)))
  io.nNonFinite := PopCount((0 until L).map(k => take(k) && !inv(k) && outAt(k).nonFinite))
  io.nFlagged   := PopCount((0 until L).map(k => take(k) && flagged(k)))
  io.nHeaders   := hdrFire

  val spNext = sp + nTaken
  io.groups.ready := io.groups.valid && spNext === g.cnt
  when(io.groups.fire) { sp := 0.U }.otherwise { sp := spNext }
  when(io.groups.fire) { hdrSent := false.B }.elsewhen(hdrFire) { hdrSent := true.B }
}
