package collide.world

import chisel3._
import chisel3.util._

/** The broad phase's counting sort of sphere indices by bucket, in on-chip RAM, one item a
  * cycle (BroadPhaseModel.countingSort is its golden model). A world is sorted in four
  * passes the caller sequences: `clear`, `count` every item, `prefix` (each count becomes its
  * bucket's start), `scatter` every item again in the same order. The counters are kept in
  * words of 2^wordLog2 buckets, so clear and prefix take a word a cycle (8 buckets by
  * default), while count and scatter read-modify-write one counter of a word a cycle. Then bucket b holds entries [end(b-1), end(b)) (end(-1) = 0), which
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
class BucketSortIO(maxItems: Int, bucketsLog2: Int, val perWord: Int) extends Bundle {
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
    /** The ends of every bucket in `bucket`'s word (for a walk that skips empty buckets a
      * word a cycle); with `bucket` the word's first, `begin` is the first one's begin. */
    val word = Output(Vec(perWord, UInt(countW.W)))
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

class BucketSort(maxItems: Int, bucketsLog2: Int, wordLog2: Int = 3) extends Module {
  require(maxItems >= 2 && bucketsLog2 >= 1 && bucketsLog2 <= 24)
  require(wordLog2 >= 0 && wordLog2 <= 5, s"wordLog2 must be 0..5, got $wordLog2")
  private val wl = math.min(wordLog2, bucketsLog2)
  override def desiredName = s"BucketSort_n${maxItems}_b${bucketsLog2}_w$wl"
  private val perWord = 1 << wl
  val io = IO(new BucketSortIO(maxItems, bucketsLog2, perWord))
  private val wordsLog2 = bucketsLog2 - wl
  private val countW = io.countW
  private def wordOf(b: UInt): UInt = if (wordsLog2 == 0) 0.U else (b >> wl)(wordsLog2 - 1, 0)
  private def laneOf(b: UInt): UInt = if (wl == 0) 0.U else b(wl - 1, 0)

  // Read-first, as block RAM returns old data on a same-cycle write: the forwarding below
  // is then what makes back-to-back repeats right, in simulation as on the FPGA.
  // A word is a flat UInt (counter l in bits l*countW up): the generator's Verilog has no
  // packed arrays, and a Mux of whole Vecs would need them.
  private val counts = SyncReadMem(1 << wordsLog2, UInt((perWord * countW).W), SyncReadMem.ReadFirst)
  private def lanes(w: UInt): Vec[UInt] = VecInit.tabulate(perWord)(l => w((l + 1) * countW - 1, l * countW))
  private def flat(v: Seq[UInt]): UInt = Cat(v.reverse)
  private val entries = SyncReadMem(maxItems, UInt((io.itemW + 1).W)) // mark ## item

  private object S extends ChiselEnum { val idle, clearing, summing = Value }
  private val state = RegInit(S.idle)
  private val walk = Reg(UInt((wordsLog2 + 1).W)) // the word clear and prefix are at
  private val used = (1.U((bucketsLog2 + 1).W) << io.usedLog2)(bucketsLog2, 0)
  // Words holding used buckets (at least one: a world of one bucket still has a word).
  private val usedWords = {
    val w = used >> wl
    Mux(w === 0.U, 1.U, w)
  }
  private val counted = RegInit(0.U(countW.W))
  private val scattered = RegInit(0.U(countW.W))
  private val bad = RegInit(false.B)
  io.busy := state =/= S.idle
  io.counted := counted; io.scattered := scattered; io.badBucket := bad

  // --- count / scatter: a two-stage read-modify-write of one counter ----------------------
  private val inRange = io.in.bits.bucket < used
  io.in.ready := state === S.idle && !io.clear && !io.prefix
  private val fire = io.in.fire && inRange
  when(io.in.fire && !inRange) { bad := true.B }
  private val rd = counts.read(wordOf(io.in.bits.bucket), fire)
  private val s1 = RegNext(fire, false.B)
  private val s1b = RegEnable(io.in.bits.bucket, fire)
  private val s1scatter = RegEnable(io.in.bits.scatter, fire)
  private val s1item = RegEnable(io.in.bits.item, fire)
  // The word written the cycle before, for the read that was issued alongside it.
  private val fwdValid = RegInit(false.B)
  private val fwdW = Reg(UInt(math.max(1, wordsLog2).W))
  private val fwdV = Reg(UInt((perWord * countW).W))
  private val oldWord = lanes(Mux(fwdValid && fwdW === wordOf(s1b), fwdV, rd))
  private val old = oldWord(laneOf(s1b))
  private val newWord = flat((0 until perWord).map(l => Mux(laneOf(s1b) === l.U, old + 1.U, oldWord(l))))
  fwdValid := s1
  when(s1) {
    fwdW := wordOf(s1b); fwdV := newWord
    when(s1scatter) { scattered := scattered + 1.U }
      .otherwise { counted := counted + 1.U }
  }
  private val scatterWrite = s1 && s1scatter
  when(scatterWrite || io.mark.valid) {
    entries.write(Mux(scatterWrite, old(io.itemW - 1, 0), io.mark.bits.addr),
      Mux(scatterWrite, 0.U(1.W) ## s1item, 1.U(1.W) ## io.mark.bits.item))
  }

  // --- clear and prefix: one word a cycle --------------------------------------------------
  private val sum = Reg(UInt(countW.W))
  private val walkW = if (wordsLog2 == 0) 0.U else walk(wordsLog2 - 1, 0)
  private val sumRead = state === S.summing && walk < usedWords
  private val sumRd = lanes(counts.read(walkW, sumRead))
  private val sumS1 = RegNext(sumRead, false.B)
  private val sumW = RegNext(walkW)
  private val sumLast = RegNext(walk + 1.U === usedWords)
  // Exclusive prefix within the word, on top of the running sum.
  private val starts = VecInit(sumRd.scanLeft(sum)(_ + _).take(perWord))
  when(io.clear && state === S.idle) {
    state := S.clearing; walk := 0.U; counted := 0.U; scattered := 0.U; bad := false.B
  }.elsewhen(io.prefix && state === S.idle) {
    state := S.summing; walk := 0.U; sum := 0.U
  }
  private val write = WireDefault(s1)
  private val writeW = WireDefault(wordOf(s1b))
  private val writeV = WireDefault(newWord)
  when(state === S.clearing) {
    write := true.B; writeW := walkW; writeV := 0.U
    walk := walk + 1.U
    when(walk + 1.U === usedWords) { state := S.idle }
  }
  when(state === S.summing && walk < usedWords) { walk := walk + 1.U }
  when(sumS1) {
    write := true.B; writeW := sumW; writeV := flat(starts)
    sum := sumRd.reduce(_ + _) + sum
    when(sumLast) { state := S.idle }
  }
  when(write) { counts.write(writeW, writeV) }

  // --- reads for the candidate generators -------------------------------------------------
  private val lb = io.lookup.bucket
  private val prev = lb - 1.U
  private val endRd = lanes(counts.read(wordOf(lb)))
  private val beginRd = lanes(counts.read(wordOf(prev)))
  private val lbZero = RegNext(lb === 0.U)
  io.lookup.end := endRd(RegNext(laneOf(lb)))
  io.lookup.word := endRd
  io.lookup.begin := Mux(lbZero, 0.U, beginRd(RegNext(laneOf(prev))))
  private val entryRd = entries.read(io.entry.addr)
  io.entry.item := entryRd(io.itemW - 1, 0)
  io.entry.mark := entryRd(io.itemW)
}
