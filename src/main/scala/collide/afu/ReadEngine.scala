package collide.afu

import chisel3._
import chisel3.util._

/** A pair line as read from host memory, with its line number in the pair list. */
class PairLine(lineBits: Int) extends Bundle {
  val line = UInt(lineBits.W)
  val data = UInt(Link.lineBits.W)
}

/** A sphere-table line to write into the on-chip table. */
class SphereLineWrite(lineBits: Int) extends Bundle {
  val line = UInt(math.max(lineBits, 1).W)
  val data = UInt(Link.lineBits.W)
}

/** Issues the run's read requests and routes the responses. Sphere-table lines go first (the
  * table must be complete before any pair can be computed); pair lines follow at once, while
  * the table's last responses are still on their way. At most `maxReads` reads are in flight
  * (one tag each), and a pair read is issued only when a slot of the pair buffer is reserved
  * for its response, so responses, which cannot be back-pressured, always find room.
  * Responses are accepted in any order; the tag says what came back.
  */
class ReadEngine(p: PucParams) extends Module {
  override def desiredName = s"ReadEngine_r${p.maxReads}_p${p.pairBufferLines}${p.name}"
  private val spLineBits = math.max(p.sphereLineBits, 1)
  val io = IO(new Bundle {
    val start       = Input(Bool())   // resets the counters; a cycle before `active`
    val active      = Input(Bool())   // the run is on: issue reads
    // The bases and line counts hold from the cycle of `start` on (the counts are taken then;
    // lineAddr reads the bases' high bits a cycle late).
    val sphereBase  = Input(UInt(Link.addrBits.W))
    val sphereLines = Input(UInt((p.sphereLineBits + 1).W))
    val pairBase    = Input(UInt(Link.addrBits.W))
    val pairLines   = Input(UInt((p.pairLineBits + 1).W))
    val rdReq       = Decoupled(new RdReq(p.tagBits))
    val rdResp      = Flipped(Valid(new RdResp(p.tagBits)))
    val sphereWrite = Valid(new SphereLineWrite(spLineBits))
    val pairs       = Decoupled(new PairLine(p.pairLineBits))
    val loaded      = Output(Bool())   // every sphere line has arrived
    val outstanding = Output(UInt(log2Ceil(p.maxReads + 1).W))
    val pairBufferEmpty = Output(Bool())
    val dbg = Output(UInt(32.W))
  })

  val sphereIssued = RegInit(0.U((p.sphereLineBits + 1).W))
  val sphereGot    = RegInit(0.U((p.sphereLineBits + 1).W))
  val pairIssued   = RegInit(0.U((p.pairLineBits + 1).W))
  val reserved     = RegInit(0.U(log2Ceil(p.pairBufferLines + 1).W)) // pair reads in flight + lines buffered
  // Lines still to ask for, counted down: "any left" is then a zero test, not a compare of the
  // issued count with the run's lines (on the path to every tag's record by the timing proxy).
  val sphereLeft   = RegInit(0.U((p.sphereLineBits + 1).W))
  val pairLeft     = RegInit(0.U((p.pairLineBits + 1).W))
  val running      = io.active
  when(io.start) {
    sphereIssued := 0.U; sphereGot := 0.U; pairIssued := 0.U
    sphereLeft := io.sphereLines; pairLeft := io.pairLines
  }

  val tags = Module(new TagPool(p.maxReads, p.tagBits, p.name))
  // What each tag in flight asked for: a pair line (else a sphere line) and its number.
  val tagIsPair = Reg(Vec(p.maxReads, Bool()))
  val tagLine   = Reg(Vec(p.maxReads, UInt(math.max(p.pairLineBits, spLineBits).W)))

  val wantSphere = running && sphereLeft =/= 0.U
  val wantPair   = running && !wantSphere && pairLeft =/= 0.U && reserved < p.pairBufferLines.U
  io.rdReq.valid     := tags.io.alloc.valid && (wantSphere || wantPair)
  io.rdReq.bits.tag  := tags.io.alloc.bits
  io.rdReq.bits.addr := Mux(wantSphere, ReadEngine.lineAddr(io.sphereBase, sphereIssued), ReadEngine.lineAddr(io.pairBase, pairIssued))
  tags.io.alloc.ready := io.rdReq.ready && (wantSphere || wantPair)
  when(io.rdReq.fire) {
    tagIsPair(tags.io.alloc.bits) := !wantSphere
    tagLine(tags.io.alloc.bits)   := Mux(wantSphere, sphereIssued, pairIssued)
    when(wantSphere) { sphereIssued := sphereIssued + 1.U; sphereLeft := sphereLeft - 1.U }
      .otherwise { pairIssued := pairIssued + 1.U; pairLeft := pairLeft - 1.U }
  }

  val rTag   = io.rdResp.bits.tag(log2Ceil(p.maxReads) - 1, 0)
  val isPair = tagIsPair(rTag)
  tags.io.free.valid := io.rdResp.valid
  tags.io.free.bits  := io.rdResp.bits.tag

  io.sphereWrite.valid     := io.rdResp.valid && !isPair
  io.sphereWrite.bits.line := tagLine(rTag)
  io.sphereWrite.bits.data := io.rdResp.bits.data
  when(io.rdResp.valid && !isPair) { sphereGot := sphereGot + 1.U }

  val buffer = Module(new Queue(new PairLine(p.pairLineBits), p.pairBufferLines, useSyncReadMem = true) {
    override def desiredName = s"PairBuffer_d${p.pairBufferLines}${p.name}"
  })
  buffer.io.enq.valid     := io.rdResp.valid && isPair
  buffer.io.enq.bits.line := tagLine(rTag)
  buffer.io.enq.bits.data := io.rdResp.bits.data
  assert(!buffer.io.enq.valid || buffer.io.enq.ready, "ReadEngine: no room for a pair line (reservation broken)")
  io.pairs <> buffer.io.deq
  reserved := reserved + (io.rdReq.fire && !wantSphere).asUInt - buffer.io.deq.fire.asUInt
  io.pairBufferEmpty := !buffer.io.deq.valid

  io.loaded      := running && sphereLeft === 0.U && sphereGot === sphereIssued // every line asked for is in
  io.outstanding := tags.io.inUse
  io.dbg := Cat(running, sphereIssued.pad(8), sphereGot.pad(8), io.sphereLines.pad(8))
}

object ReadEngine {
  /** base + off with the carry chain of the offset's width, not the address's: the base's high
    * bits come as they are or from a register holding them plus one, a cycle late. So the base
    * must hold from the cycle before the sum is used. (A 64-bit add here was the read engine's
    * slowest path by the timing proxy: 64 carry cells.) */
  def lineAddr(base: UInt, off: UInt): UInt = {
    val k       = off.getWidth + 1
    val lo      = base(k - 1, 0) +& off
    val hi      = base(base.getWidth - 1, k)
    val hiPlus1 = RegNext(hi + 1.U)
    Cat(Mux(lo(k), hiPlus1, hi), lo(k - 1, 0))
  }
}
