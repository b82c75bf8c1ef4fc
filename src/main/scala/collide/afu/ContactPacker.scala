package collide.afu

import chisel3._
import chisel3.util._

/** A contact line bound for host memory. */
class LineWrite extends Bundle {
  val addr = UInt(Link.addrBits.W)
  val data = UInt(Link.lineBits.W)
}

/** Packs records into lines, R = recordsPerLine of the layout (docs/afu-interface.md,
  * "Contacts"). Compact mode: record n (the running hit count) lives at line n / R, slot
  * n % R. Dense mode: record k is pair k, and since pair lines may arrive in any order each
  * pair line's 16 records start a contact line of their own: record k at line
  * (k / 16) * ceil(16 / R) + (k % 16) / R, slot (k % 16) % R (the plain k / R whenever R
  * divides 16). Either way the records of one cycle are consecutive, so the packer only
  * counts. It holds at most R - 1 records. In compact mode it takes up to R a cycle and
  * keeps what passes the line it completes, so the write port can leave with a full line
  * every cycle; in dense mode it asks for no more than complete the line (a pair line's
  * end must end a line too). Either way at most one line leaves a cycle. Records at or past
  * CONTACT_CAPACITY are written as zero, and a line holding none below it is dropped.
  * `flush` (end of run) writes a held partial line with its other slots zero. Masked
  * layouts' mask headers are slots like records: the packer does not tell them apart.
  */
class ContactPacker(p: PucParams) extends Module {
  private val lay = p.layout
  private val R = lay.recordsPerLine
  private val ppl = lay.pairsPerLine
  private val recBits = lay.recordBits
  private val idxBits = lay.pairIndexBits
  override def desiredName = s"ContactPacker_w${p.linkWidth}_${lay.records.name}_r$R${p.name}"
  val io = IO(new Bundle {
    val start    = Input(Bool())
    val dense    = Input(Bool())
    val numPairs = Input(UInt(idxBits.W))
    val base     = Input(UInt(Link.addrBits.W))
    val capacity = Input(UInt(Link.csrDataBits.W))
    val room     = Output(UInt(log2Ceil(R + 1).W))
    val recs     = Input(Vec(R, new ContactRecord(lay)))
    val nRecs    = Input(UInt(log2Ceil(R + 1).W))
    val flush    = Input(Bool())
    val idle     = Output(Bool())   // nothing held
    val lines    = Decoupled(new LineWrite)
  })

  val q = Module(new Queue(new LineWrite, p.writeQueueLines) {
    override def desiredName = s"ContactLineQueue_d${p.writeQueueLines}${p.name}"
  })
  // The queue holds each line's number in the buffer; the base address is added as it
  // leaves, so no 64-bit sum sits on the path that forms a line.
  io.lines <> q.io.deq
  io.lines.bits.addr := io.base + q.io.deq.bits.addr

  val fill     = RegInit(0.U(log2Ceil(R + 1).W))     // records held, < R
  val held     = Reg(Vec(math.max(R - 1, 1), UInt(recBits.W)))
  val count    = RegInit(0.U((idxBits + 1).W))        // compact: records so far
  val lineNo   = RegInit(0.U((idxBits + 1).W))        // compact: lines so far
  val heldLine = Reg(UInt((idxBits + 1).W))           // the held records' line
  val heldRn   = Reg(UInt((idxBits + 1).W))           // record number of its slot 0
  io.room := Mux(q.io.enq.ready, Mux(io.dense, R.U - fill, R.U), 0.U)
  io.idle := fill === 0.U

  // Dense line of a pair: (k / 16) * ceil(16 / R) + (k % 16) / R, the last term from a table.
  private val linesPerPairLine = (ppl + R - 1) / R
  private def denseLine(k: UInt): UInt = {
    val inLine = VecInit.tabulate(ppl)(i => (i / R).U(log2Ceil(ppl + 1).W))(k(log2Ceil(ppl) - 1, 0))
    ((k >> log2Ceil(ppl)) * linesPerPairLine.U) +& inLine
  }
  val first    = io.recs(0)
  val lineOf   = Mux(fill =/= 0.U, heldLine, Mux(io.dense, denseLine(first.pair), lineNo))
  val rnOf     = Mux(fill =/= 0.U, heldRn, Mux(io.dense, first.pair.pad(idxBits + 1), count))

  // Record rn + s is below the capacity when rn < capacity - s: each slot's bound registered
  // and saturated past any record number, so the per-cycle test is a short compare, not a
  // 64-bit sum and compare (the packer's slowest path by the timing proxy). The capacity is
  // set before a run starts, many cycles before its first record.
  private val rnW = idxBits + 1
  val capLess = Reg(Vec(R, UInt((rnW + 1).W)))
  for (s <- 0 until R)
    capLess(s) := Mux(io.capacity >= ((BigInt(1) << rnW) + s).U, (BigInt(1) << rnW).U, Mux(io.capacity > s.U, io.capacity - s.U, 0.U))
  val total = fill +& io.nRecs   // < 2R: at most one full line
  private def idx(x: UInt): UInt = if (R == 1) 0.U else x(log2Ceil(R) - 1, 0)
  // The three record numbers a line can start from, each compared with the slot's bound at
  // once, and the answer chosen after (not the number chosen, then compared).
  private def below(s: Int) = {
    val first = io.recs(0).pair.pad(idxBits + 1)
    Mux(fill =/= 0.U, heldRn < capLess(s), Mux(io.dense, first < capLess(s), count < capLess(s)))
  }
  private val fnW = log2Ceil(R + 1)
  val slots = VecInit.tabulate(R) { s =>
    val fromHeld = if (s < R - 1) held(s) else 0.U(recBits.W)
    val inHeld = collide.util.Table(fill, 1)(f => if (s < f) 1 else 0).asBool
    val v = Mux(inHeld, fromHeld, io.recs(collide.util.Table(fill, math.max(log2Ceil(R), 1))(f => ((s - f) % R + R) % R)).bits)
    val inLine = collide.util.Table(Cat(fill, io.nRecs), 1)(x => if (s < (x >> fnW) + (x & ((1 << fnW) - 1))) 1 else 0).asBool
    Mux(inLine && below(s), v, 0.U(recBits.W))
  }
  // Dense: a pair line's last record (pair 15 of its line, or the run's last pair) ends the line.
  val lastIn   = io.recs(idx(io.nRecs - 1.U)).pair
  val endsPairLine = io.dense && io.nRecs =/= 0.U &&
    (lastIn(log2Ceil(ppl) - 1, 0).andR || lastIn === io.numPairs - 1.U)
  val emit = q.io.enq.ready && (total >= R.U || (endsPairLine && total =/= 0.U) || (io.flush && total =/= 0.U))
  // Compact: the records that pass the completed line stay, shifted to slot 0.
  val carry = Mux(total > R.U, total - R.U, 0.U)
  q.io.enq.valid     := emit && rnOf < capLess(0)
  q.io.enq.bits.addr := lineOf
  q.io.enq.bits.data := Cat(slots.reverse).pad(Link.lineBits)
  when(emit) {
    fill := carry
    when(!io.dense) { lineNo := lineNo + 1.U }
    heldLine := lineNo + 1.U; heldRn := rnOf + R.U
    for (s <- 0 until R - 1) when(s.U < carry) {
      held(s) := io.recs(idx(s.U +& R.U - fill)).bits
    }
  }.otherwise {
    fill := total
    heldLine := lineOf; heldRn := rnOf
    for (s <- 0 until R - 1) when(s.U < total) { held(s) := slots(s) }
  }
  when(!io.dense) { count := count + io.nRecs }
  when(io.start) { fill := 0.U; count := 0.U; lineNo := 0.U }
  assert(io.nRecs <= io.room, "ContactPacker: more records than room")
  assert(!q.io.enq.valid || q.io.enq.ready, "ContactPacker: line queue overflow")
}
