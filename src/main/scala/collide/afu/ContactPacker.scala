package collide.afu

import chisel3._
import chisel3.util._

/** A contact line bound for host memory. */
class LineWrite extends Bundle {
  val addr = UInt(Link.addrBits.W)
  val data = UInt(Link.lineBits.W)
}

/** Packs records into lines. Record number rn: the pair index in dense mode, the running hit
  * count in compact mode; record rn lives at line rn / R, slot rn % R (R records a line).
  * Records come in order with consecutive numbers within a pair line, so at most one line
  * completes a cycle: the packer asks for one record less while it holds a half line. A
  * line holding no record below CONTACT_CAPACITY is dropped; records at or past it are zero.
  * `flush` (end of run) writes a held half line with its other record zero.
  */
class ContactPacker(p: PucParams) extends Module {
  override def desiredName = s"ContactPacker_w${p.linkWidth}${p.name}"
  private val R = p.layout.recordsPerLine
  private val w = p.linkWidth
  val io = IO(new Bundle {
    val start    = Input(Bool())
    val dense    = Input(Bool())
    val numPairs = Input(UInt(p.layout.pairIndexBits.W))
    val base     = Input(UInt(Link.addrBits.W))
    val capacity = Input(UInt(Link.csrDataBits.W))
    val room     = Output(UInt(log2Ceil(R + 1).W))
    val recs     = Input(Vec(R, new ContactRecord(w)))
    val nRecs    = Input(UInt(log2Ceil(R + 1).W))
    val flush    = Input(Bool())
    val idle     = Output(Bool())   // nothing held
    val lines    = Decoupled(new LineWrite)
  })

  private def pack(r: ContactRecord): UInt =
    if (w == 32) Cat(r.flags, r.pair, r.depth, r.nz, r.ny, r.nx, r.pz, r.py, r.px)
    else Cat(r.flags.pad(32), r.pair.pad(32), r.depth, r.nz, r.ny, r.nx, r.pz, r.py, r.px)

  val q = Module(new Queue(new LineWrite, p.writeQueueLines) {
    override def desiredName = s"ContactLineQueue_d${p.writeQueueLines}${p.name}"
  })
  io.lines <> q.io.deq
  val hitCount = RegInit(0.U(p.layout.pairIndexBits.W)) // compact record numbers
  when(io.start) { hitCount := 0.U }

  val rn = VecInit.tabulate(R)(r => Mux(io.dense, io.recs(r).pair, hitCount + r.U))
  private val recBits = p.layout.recordBytes * 8

  if (R == 1) {
    io.room := q.io.enq.ready.asUInt
    val ok = rn(0) < io.capacity
    q.io.enq.valid := io.nRecs === 1.U && ok
    q.io.enq.bits.addr := io.base + rn(0)
    q.io.enq.bits.data := pack(io.recs(0))
    io.idle := true.B
  } else {
    // R == 2 (binary32)
    val held      = RegInit(false.B)
    val heldRec   = Reg(new ContactRecord(w))
    val heldRn    = Reg(UInt(p.layout.pairIndexBits.W))
    io.room := Mux(q.io.enq.ready, Mux(held, 1.U, 2.U), 0.U)
    io.idle := !held
    def inCap(x: UInt) = x < io.capacity
    def recOrZero(r: ContactRecord, x: UInt): UInt = Mux(inCap(x), pack(r), 0.U(recBits.W))
    val a = io.recs(0); val b = io.recs(1); val ra = rn(0); val rb = rn(1)
    val lastA = io.dense && ra === io.numPairs - 1.U && !ra(0) // a final half line (dense)
    val enqValid = WireDefault(false.B)
    val enqRn    = WireDefault(ra)   // number of the line's slot-0 record
    val enqData  = WireDefault(0.U(Link.lineBits.W))
    when(io.flush && held && q.io.enq.ready) {
      enqValid := true.B; enqRn := heldRn; enqData := Cat(0.U(recBits.W), recOrZero(heldRec, heldRn))
      held := false.B
    }.elsewhen(held) {
      when(io.nRecs === 1.U) { // a completes the held line
        enqValid := true.B; enqRn := heldRn
        enqData := Cat(recOrZero(a, ra), recOrZero(heldRec, heldRn))
        held := false.B
      }
    }.otherwise {
      when(io.nRecs === 2.U) {
        when(lastA) { // a alone, b starts the next line
          enqValid := true.B; enqRn := ra; enqData := Cat(0.U(recBits.W), recOrZero(a, ra))
          held := true.B; heldRec := b; heldRn := rb
        }.otherwise {
          enqValid := true.B; enqRn := ra; enqData := Cat(recOrZero(b, rb), recOrZero(a, ra))
        }
      }.elsewhen(io.nRecs === 1.U) {
        when(lastA) {
          enqValid := true.B; enqRn := ra; enqData := Cat(0.U(recBits.W), recOrZero(a, ra))
        }.otherwise { held := true.B; heldRec := a; heldRn := ra }
      }
    }
    q.io.enq.valid := enqValid && inCap(enqRn)
    q.io.enq.bits.addr := io.base + (enqRn >> 1)
    q.io.enq.bits.data := enqData
    assert(!(held && io.nRecs =/= 0.U && rn(0)(0) === 0.U && !io.flush), "ContactPacker: record stream out of order")
  }
  when(!io.dense) { hitCount := hitCount + io.nRecs }
  when(io.start) { hitCount := 0.U }
  assert(!q.io.enq.valid || q.io.enq.ready, "ContactPacker: line queue overflow")
}
