package collide.formal

import chisel3._
import chisel3.util._
import collide.afu._

/** ContactPacker in compact mode, fed records (any bits, up to its room a cycle) by a
  * collector that stops once `flush` (end of run, held) is up, with a write port ready or not
  * at will, a capacity and a base that hold from reset. The wrapper numbers the records as
  * they come (record n: the n-th) and watches one record number, a free input held from reset.
  *
  * Proven: the k-th line out is line k of the buffer (base + k: lines in order, none twice,
  * none skipped); a line holding the watched record's slot carries that record's bits in its
  * slot if it came and lies below the capacity, zero otherwise, and at most one line holds
  * that slot; once flushed and empty, the lines written are exactly ceil(min(records,
  * capacity) / R), and the watched record (if it came and fits) was written; the packer's
  * own assertions (no more records than room, no line queue overflow).
  * SeededBug: the wrapper counts a cycle's records twice when R came at once (a double count). */
class ContactPackerFormal(p: PucParams, check: Check = Check.Prove) extends Module {
  private val lay = p.layout
  private val R = lay.recordsPerLine
  private val cw = 10 // records and lines counted: R a cycle, well under 2^10 in the bound
  require(isPow2(R), "the wrapper's line and slot of a record number are a shift and a mask")
  val io = IO(new Bundle {
    val base     = Input(UInt(Link.addrBits.W))
    val capacity = Input(UInt(Link.csrDataBits.W))
    val recs     = Input(Vec(R, new ContactRecord(lay)))
    val nRecs    = Input(UInt(log2Ceil(R + 1).W))
    val flush    = Input(Bool())
    val ready    = Input(Bool())
    val watch    = Input(UInt(cw.W))
  })
  val dut = Module(new ContactPacker(p))
  private val cyc = FormalEnv.cycles(4)
  dut.io.start := false.B // reset starts the run (start does what reset does to the counts)
  dut.io.dense := false.B
  dut.io.numPairs := 0.U
  dut.io.base := io.base
  dut.io.capacity := io.capacity
  dut.io.recs := io.recs
  dut.io.nRecs := io.nRecs
  dut.io.flush := io.flush
  dut.io.lines.ready := io.ready

  // ---- the environment
  FormalEnv.stable(io.base); FormalEnv.stable(io.capacity); FormalEnv.stable(io.watch)
  assume(io.nRecs <= dut.io.room, "no more records than room")
  // The capacity's per-slot bounds are registered: set a cycle before the first record.
  when(cyc === 0.U) { assume(io.nRecs === 0.U && !io.flush) }
  private val flushed = RegInit(false.B)
  when(io.flush) { flushed := true.B }
  when(flushed) { assume(io.flush && io.nRecs === 0.U, "flush holds, and no record comes after it") }

  // ---- records in: numbered, the watched one's bits kept
  val recsIn = RegInit(0.U(cw.W))
  private val counted = if (check == Check.SeededBug) Mux(io.nRecs === R.U, (2 * R).U, io.nRecs) else io.nRecs
  recsIn := recsIn + counted
  private val watchBits = Reg(UInt(lay.recordBits.W))
  private val watchIn = RegInit(false.B)
  // The watched record arriving now: a line may leave with it in the cycle it comes.
  private val arriving = VecInit.tabulate(R)(r => r.U < io.nRecs && recsIn + r.U === io.watch)
  private val arrivingBits = Mux1H(arriving, io.recs.map(_.bits))
  when(arriving.asUInt.orR) { watchBits := arrivingBits; watchIn := true.B }
  private val watchInNow = watchIn || arriving.asUInt.orR
  private val watchBitsNow = Mux(watchIn, watchBits, arrivingBits)

  // ---- lines out
  private val out = dut.io.lines
  val linesOut = RegInit(0.U(cw.W))
  when(out.fire) { linesOut := linesOut + 1.U }
  private val lineNo = out.bits.addr - io.base
  when(out.valid) { assert(lineNo === linesOut, "the k-th line out is line k of the buffer") }
  private val watchLine = io.watch >> log2Ceil(R)
  private val watchSlot = if (R == 1) 0.U else io.watch(log2Ceil(R) - 1, 0)
  private val slotBits = VecInit.tabulate(R)(s => out.bits.data((s + 1) * lay.recordBits - 1, s * lay.recordBits))(watchSlot)
  private val fits = io.watch < io.capacity
  private val watchOut = RegInit(0.U(2.W))
  when(out.fire && lineNo === watchLine) {
    watchOut := watchOut + 1.U
    assert(watchOut === 0.U, "at most one line holds the watched record's slot")
    assert(slotBits === Mux(watchInNow && fits, watchBitsNow, 0.U), "the watched slot holds its record, or zero")
  }
  // Done: flushed, nothing held, the line queue empty (a line waiting would show valid).
  private val done = flushed && RegNext(flushed, false.B) && dut.io.idle && !out.valid
  private val capped = Mux(io.capacity < recsIn, io.capacity(cw - 1, 0), recsIn)
  when(done) {
    assert(linesOut === (capped +& (R - 1).U) >> log2Ceil(R), "every line with a record below the capacity was written")
    when(watchIn && fits) { assert(watchOut === 1.U, "the watched record was written") }
  }
  FormalEnv.finish(check, done && watchIn && fits && watchOut === 1.U && linesOut >= 2.U,
    "flushed and empty after two lines, the watched record among them")
}
