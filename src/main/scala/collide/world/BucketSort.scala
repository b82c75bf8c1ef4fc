package collide.world

import chisel3._
import chisel3.util._

/** The broad phase's counting sort of sphere indices by bucket, in on-chip RAM, one item a
  * cycle (BroadPhaseModel.countingSort is its golden model). A world is sorted in four
  * passes the caller sequences: `clear` (one bucket a cycle), `count` every item, `prefix`
  * (one bucket a cycle: each count becomes its bucket's start), `scatter` every item again in
  * the same order. Then bucket b holds entries [end(b-1), end(b)) (end(-1) = 0), which
  * `lookup` and `entry` read with one cycle of latency.
  *
  * Count and scatter are read-modify-writes of one counter a cycle; a write is forwarded to
  * the read issued in the same cycle, so repeated buckets need no stall. Contract: scatter
  * exactly the items counted (the caller checks counted === scattered); a bucket at or above
  * the used range is refused and latched in badBucket, never written.
  *
  * Each entry carries a mark bit for the candidate generator (which entries of a bucket it
  * has put in a chunk already): scatter writes it clear, so a new world needs no clearing
  * pass, and `mark` sets it (rewriting the item it was given). Never mark while scattering.
  */
class BucketSortIO(maxItems: Int, bucketsLog2: Int) extends Bundle {
  val itemW = log2Ceil(maxItems)
  val countW = log2Ceil(maxItems + 1)
  /** log2 of the buckets in use this world (<= bucketsLog2): what clear and prefix walk. */
  val usedLog2 = Input(UInt(log2Ceil(bucketsLog2 + 1).W))
  val clear = Input(Bool())  // pulse: start clearing
  val prefix = Input(Bool()) // pulse: start the prefix sum
  val busy = Output(Bool())  // clearing or summing; in is not ready meanwhile
  val in = Flipped(Decoupled(new Bundle {
    val scatter = Bool() // false: count this item's bucket; true: place the item
    val bucket = UInt(bucketsLog2.W)
    val item = UInt(itemW.W)
  }))
  val lookup = new Bundle {
    val bucket = Input(UInt(bucketsLog2.W))
    val begin = Output(UInt(countW.W)) // the cycle after
    val end = Output(UInt(countW.W))
  }
  val entry = new Bundle {
    val addr = Input(UInt(itemW.W))
    val item = Output(UInt(itemW.W)) // the cycle after
    val mark = Output(Bool())
  }
  val mark = Flipped(Valid(new Bundle {
    val addr = UInt(itemW.W)
    val item = UInt(itemW.W)
  }))
  val counted = Output(UInt(countW.W))
  val scattered = Output(UInt(countW.W))
  val badBucket = Output(Bool())
}

class BucketSort(maxItems: Int, bucketsLog2: Int) extends Module {
  require(maxItems >= 2 && bucketsLog2 >= 1 && bucketsLog2 <= 24)
  override def desiredName = s"BucketSort_n${maxItems}_b$bucketsLog2"
  val io = IO(new BucketSortIO(maxItems, bucketsLog2))
  private val buckets = 1 << bucketsLog2
  private val countW = io.countW

  // Read-first, as block RAM returns old data on a same-cycle write: the forwarding below
  // is then what makes back-to-back repeats right, in simulation as on the FPGA.
  private val counts = SyncReadMem(buckets, UInt(countW.W), SyncReadMem.ReadFirst)
  private val entries = SyncReadMem(maxItems, UInt((io.itemW + 1).W)) // mark ## item

  private object S extends ChiselEnum { val idle, clearing, summing = Value }
  private val state = RegInit(S.idle)
  private val walk = Reg(UInt((bucketsLog2 + 1).W))
  private val used = (1.U((bucketsLog2 + 1).W) << io.usedLog2)(bucketsLog2, 0)
  private val counted = RegInit(0.U(countW.W))
  private val scattered = RegInit(0.U(countW.W))
  private val bad = RegInit(false.B)
  io.busy := state =/= S.idle
  io.counted := counted; io.scattered := scattered; io.badBucket := bad

  // --- count / scatter: a two-stage read-modify-write -------------------------------------
  private val inRange = io.in.bits.bucket < used
  io.in.ready := state === S.idle && !io.clear && !io.prefix
  private val fire = io.in.fire && inRange
  when(io.in.fire && !inRange) { bad := true.B }
  private val rd = counts.read(io.in.bits.bucket, fire)
  private val s1 = RegNext(fire, false.B)
  private val s1b = RegEnable(io.in.bits.bucket, fire)
  private val s1scatter = RegEnable(io.in.bits.scatter, fire)
  private val s1item = RegEnable(io.in.bits.item, fire)
  // The write of the previous cycle, for the read that was issued alongside it.
  private val fwdValid = RegInit(false.B)
  private val fwdB = Reg(UInt(bucketsLog2.W))
  private val fwdV = Reg(UInt(countW.W))
  private val old = Mux(fwdValid && fwdB === s1b, fwdV, rd)
  private val next = old + 1.U
  fwdValid := s1
  when(s1) {
    counts.write(s1b, next)
    fwdB := s1b; fwdV := next
    when(s1scatter) { scattered := scattered + 1.U }
      .otherwise { counted := counted + 1.U }
  }
  private val scatterWrite = s1 && s1scatter
  when(scatterWrite || io.mark.valid) {
    entries.write(Mux(scatterWrite, old(io.itemW - 1, 0), io.mark.bits.addr),
      Mux(scatterWrite, 0.U(1.W) ## s1item, 1.U(1.W) ## io.mark.bits.item))
  }

  // --- clear and prefix: one bucket a cycle ---------------------------------------------
  private val sum = Reg(UInt(countW.W))
  private val sumRd = counts.read(walk(bucketsLog2 - 1, 0), state === S.summing && walk < used)
  private val sumS1 = RegNext(state === S.summing && walk < used, false.B)
  private val sumB = RegNext(walk(bucketsLog2 - 1, 0))
  when(io.clear && state === S.idle) {
    state := S.clearing; walk := 0.U; counted := 0.U; scattered := 0.U; bad := false.B
  }.elsewhen(io.prefix && state === S.idle) {
    state := S.summing; walk := 0.U; sum := 0.U
  }
  when(state === S.clearing) {
    counts.write(walk(bucketsLog2 - 1, 0), 0.U)
    walk := walk + 1.U
    when(walk + 1.U === used) { state := S.idle }
  }
  when(state === S.summing) {
    when(walk < used) { walk := walk + 1.U }
  }
  when(sumS1) {
    counts.write(sumB, sum) // exclusive: the start of this bucket
    sum := sum + sumRd
    when(sumB +& 1.U === used) { state := S.idle }
  }

  // --- reads for the candidate generators -------------------------------------------------
  private val lb = io.lookup.bucket
  private val endRd = counts.read(lb)
  private val beginRd = counts.read(lb - 1.U)
  private val lbZero = RegNext(lb === 0.U)
  io.lookup.end := endRd
  io.lookup.begin := Mux(lbZero, 0.U, beginRd)
  private val entryRd = entries.read(io.entry.addr)
  io.entry.item := entryRd(io.itemW - 1, 0)
  io.entry.mark := entryRd(io.itemW)
}
