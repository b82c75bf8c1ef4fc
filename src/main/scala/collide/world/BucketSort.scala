package collide.world

import chisel3._
import chisel3.util._
import collide.fp.Pipeline
import collide.util.Prefix

/** The broad phase's counting sort of sphere indices by bucket, in on-chip RAM
  * (BroadPhaseModel.countingSort is its golden model), `ports` items a cycle, kept in
  * `copies` identical copies the candidate generators read one each. A world is sorted in
  * four passes the caller sequences: `clear`, `count` every item, `prefix` (each count
  * becomes its bucket's start), `scatter` every item again. Port p counts and scatters the
  * p-th contiguous part of the items, in the same order both times, so the entries come out
  * in the order of the items, as one port would leave them. Then bucket b holds entries
  * [end(b-1), end(b)) (end(-1) = 0) in every copy, which `lookup(c)` and `entry(c)` read with
  * one cycle of latency.
  *
  * Counters are kept in words of 2^wordLog2 buckets, so clear and prefix take a word a
  * cycle (8 buckets by default). Port p owns a table of counters, its cursors: count and
  * scatter read-modify-write one counter of it a cycle (a write is forwarded to the read
  * issued in the same cycle, so repeated buckets need no stall). The prefix sum reads every
  * port's count of a word and writes port p's cursor the bucket's start plus the counts of
  * ports before p, so each port scatters into its own share of the bucket. The last port's
  * table is copy 0's, whose cursors end at end(b); copies 1 and up are written end(b) by the
  * prefix sum and never counted in. So `ports` = 2 costs one table more than 1.
  *
  * Entries: each copy's table of sphere indices takes both ports' scatter writes in a cycle
  * (a true dual-port block RAM, one port of it also reading; with one sort port, a simple
  * dual-port one: a write port shared by placements and marks, and a read port). Yosys 0.23's
  * Cyclone V library has simple dual-port block RAM only, so its area proxy maps the
  * two-port entries to flip-flops (docs/afu.md). Each entry
  * carries a mark bit for the candidate generator (which entries of a bucket it has put in a
  * chunk already): scatter writes it clear, so a new world needs no clearing pass, and
  * `mark(c)` sets it in copy c (rewriting the item it was given). Never mark while
  * scattering: generation reads one port and marks through the other.
  *
  * Items may be wider than positions (`itemBits`): a sort of half the table (one group of the
  * broad phase's four sort ports) holds whole sphere indices in half as many entries.
  *
  * Contract: scatter exactly the items counted, through the same port (the caller checks
  * counted === scattered); a bucket at or above the used range is refused and latched in
  * badBucket, never written.
  */
class BucketSortIO(maxItems: Int, bucketsLog2: Int, val perWord: Int, copies: Int, ports: Int, itemBits: Int,
                   clearBehind: Boolean = false) extends Bundle {
  /** Width of an item (what an entry holds) and of a position in the entries (maxItems deep). */
  val itemW = if (itemBits > 0) itemBits else log2Ceil(maxItems)
  val posW = log2Ceil(maxItems)
  val countW = log2Ceil(maxItems + 1)
  /** log2 of the buckets in use this world (<= bucketsLog2): what clear and prefix walk. */
  val usedLog2 = Input(UInt(log2Ceil(bucketsLog2 + 1).W))
  /** The buckets the prefix sum covers, a whole number of words (BroadPhaseModel.walkBuckets):
    * those in use, or fewer where no sphere's bucket or lookup lies past them. */
  val walkBuckets = Input(UInt((bucketsLog2 + 1).W))
  val clear = Input(Bool())  // pulse: start clearing
  val prefix = Input(Bool()) // pulse: start the prefix sum
  /** clearBehind: pulse once the scatter is over (its last write landed): the cursors are
    * cleared behind it, while the lookups serve the world, so the next world's clear is done. */
  val scrub = if (clearBehind) Some(Input(Bool())) else None
  val busy = Output(Bool())  // clearing or summing; in is not ready meanwhile
  val in = Vec(ports, Flipped(Decoupled(new Bundle {
    val scatter = Bool() // false: count this item's bucket; true: place the item
    val bucket = UInt(bucketsLog2.W)
    val item = UInt(itemW.W)
  })))
  val lookup = Vec(copies, new Bundle {
    val bucket = Input(UInt(bucketsLog2.W))
    val begin = Output(UInt(countW.W)) // the cycle after
    val end = Output(UInt(countW.W))
    /** The ends of every bucket in `bucket`'s word (for a walk that skips empty buckets a
      * word a cycle); with `bucket` the word's first, `begin` is the first one's begin. */
    val word = Output(Vec(perWord, UInt(countW.W)))
  })
  val entry = Vec(copies, new Bundle {
    val addr = Input(UInt(posW.W))
    val item = Output(UInt(itemW.W)) // the cycle after
    val mark = Output(Bool())
  })
  val mark = Vec(copies, Flipped(Valid(new Bundle {
    val addr = UInt(posW.W)
    val item = UInt(itemW.W)
  })))
  val counted = Output(UInt(countW.W))
  val scattered = Output(UInt(countW.W))
  val badBucket = Output(Bool())
}

class BucketSort(maxItems: Int, bucketsLog2: Int, wordLog2: Int = 3, copies: Int = 1, ports: Int = 1, itemBits: Int = 0,
                 clearBehind: Boolean = false) extends Module {
  require(itemBits == 0 || itemBits >= log2Ceil(maxItems), s"itemBits $itemBits cannot name $maxItems items")
  require(maxItems >= 2 && bucketsLog2 >= 1 && bucketsLog2 <= 24)
  require(wordLog2 >= 0 && wordLog2 <= 5, s"wordLog2 must be 0..5, got $wordLog2")
  require(copies >= 1 && copies <= 32, s"copies must be 1..32 (one a lane), got $copies")
  require(ports == 1 || ports == 2, s"ports must be 1 or 2 (a block RAM's two write ports), got $ports")
  private val wl = math.min(wordLog2, bucketsLog2)
  override def desiredName = s"BucketSort_n${maxItems}_b${bucketsLog2}_w$wl" +
    (if (copies > 1) s"_c$copies" else "") + (if (ports > 1) s"_p$ports" else "") + (if (itemBits > 0) s"_i$itemBits" else "") +
    (if (clearBehind) "_cb" else "")
  private val perWord = 1 << wl
  val io = IO(new BucketSortIO(maxItems, bucketsLog2, perWord, copies, ports, itemBits, clearBehind))
  private val wordsLog2 = bucketsLog2 - wl
  private val countW = io.countW
  private val itemW = io.itemW
  private val posW = io.posW
  private def wordOf(b: UInt): UInt = if (wordsLog2 == 0) 0.U else (b >> wl)(wordsLog2 - 1, 0)
  private def laneOf(b: UInt): UInt = if (wl == 0) 0.U else b(wl - 1, 0)
  private def lanes(w: UInt): Vec[UInt] = VecInit.tabulate(perWord)(l => w((l + 1) * countW - 1, l * countW))
  private def flat(v: Seq[UInt]): UInt = Cat(v.reverse)

  // Read-first, as block RAM returns old data on a same-cycle write: the forwarding below
  // is then what makes back-to-back repeats right, in simulation as on the FPGA.
  // A word is a flat UInt (counter l in bits l*countW up): the generator's Verilog has no
  // packed arrays, and a Mux of whole Vecs would need them.
  private def counterTable() = SyncReadMem(1 << wordsLog2, UInt((perWord * countW).W), SyncReadMem.ReadFirst)
  /** The lookup tables, one per copy; tables(0) is also the last port's cursors, except with
    * clearBehind, where the cursors are apart from every lookup table (one table more), so
    * that they can be cleared while the lookups serve the world. */
  private val tables = Seq.fill(copies)(counterTable())
  /** Each port's cursors: a table of its own, but for the last port, copy 0's (clearBehind: its own). */
  private val cursors = if (clearBehind) Seq.fill(ports)(counterTable()) else Seq.fill(ports - 1)(counterTable()) :+ tables.head
  private val entries = Seq.fill(copies)(SyncReadMem(maxItems, UInt((itemW + 1).W))) // mark ## item

  private object S extends ChiselEnum { val idle, clearing, summing = Value }
  private val state = RegInit(S.idle)
  private val walk = Reg(UInt((wordsLog2 + 1).W)) // the word clear and prefix are at
  private val used = (1.U((bucketsLog2 + 1).W) << io.usedLog2)(bucketsLog2, 0)
  // Words holding used buckets (a world of one bucket still has a word), and those the prefix sum covers.
  private val usedWords = BucketSort.spans(used, wl)
  /** The words a clearing pass covers: the world's used ones; with clearBehind, the last world's
    * (behind its scatter), or every word while the cursors may hold anything (after reset). */
  private val clearTo = Reg(UInt((wordsLog2 + 1).W))
  /** clearBehind: every cursor is zero (a clear has nothing to do). */
  private val clean = RegInit(false.B)
  private val sumWords = BucketSort.spans(io.walkBuckets, wl)
  private val counted = RegInit(0.U(countW.W))
  private val scattered = RegInit(0.U(countW.W))
  private val bad = RegInit(false.B)
  io.busy := state =/= S.idle
  io.counted := counted; io.scattered := scattered; io.badBucket := bad
  private val walkW = if (wordsLog2 == 0) 0.U else walk(wordsLog2 - 1, 0)

  // --- clear and prefix: one word a cycle --------------------------------------------------
  // The prefix sum is a pipeline, a word a cycle: read the ports' counters; their totals and
  // each port's offset (the counts of the ports before it); the totals' prefix within the word,
  // a level of adders a cycle; each cursor's offset within the word; then, in one adder each,
  // the running sum added (the only recurrence: sum += the word's total).
  private val sum = Reg(UInt(countW.W))
  private val sumRead = state === S.summing && walk < sumWords
  private val sumRd = cursors.map(t => lanes(t.read(walkW, sumRead)))
  /** Cycles from the counters' read data to the cycle their word is written. */
  private val sumStages = BucketSort.prefixStages(perWord)
  private def sumPipe[T <: Data](x: T, n: Int): T = Pipeline(x, n, true.B)
  private val sumApply = sumPipe(RegNext(sumRead, false.B), sumStages)
  private val sumW = sumPipe(RegNext(walkW), sumStages)
  private val sumLast = sumPipe(RegNext(walk + 1.U === sumWords), sumStages)
  // Per bucket of the word: every port's count and their total (registered).
  private val totals = RegNext(VecInit.tabulate(perWord)(j => sumRd.map(_(j)).reduce(_ + _)))
  private val portOffsets = (0 until ports).map(p => RegNext(VecInit.tabulate(perWord)(j =>
    sumRd.take(p).map(_(j)).foldLeft(0.U(countW.W))(_ + _))))
  // The totals' inclusive prefix within the word, a level a cycle.
  private val incl = VecInit(Prefix.levels[UInt](totals, v => v.map(x => RegNext(x)))(_ + _))
  private val inclAt = Prefix.levelCount(perWord)
  // Bucket j's start within the word (the prefix before it), plus port p's offset, a cycle on.
  private val offsetsP = portOffsets.map(o => sumPipe(o, inclAt))
  private val preStarts = offsetsP.map(o => RegNext(VecInit.tabulate(perWord)(j => if (j == 0) o(j) else incl(j - 1) + o(j))))
  private val preEnds = RegNext(incl)
  /** Port p's cursor for bucket j: the running sum plus its start within the word. */
  private def portStart(p: Int, j: Int): UInt = sum + preStarts(p)(j)
  private class Place extends Bundle { val pos = UInt(posW.W); val item = UInt(itemW.W) }
  /** Each port's scatter placement this cycle (the read-modify-write's second stage). */
  private val place = Wire(Vec(ports, Valid(new Place)))
  private val countFires = Wire(Vec(ports, Bool()))
  counted := counted + PopCount(countFires) // (a clear, below, wins)
  scattered := scattered + PopCount(place.map(_.valid))
  if (!clearBehind) {
    when(io.clear && state === S.idle) {
      state := S.clearing; walk := 0.U; counted := 0.U; scattered := 0.U; bad := false.B
    }.elsewhen(io.prefix && state === S.idle) {
      state := S.summing; walk := 0.U; sum := 0.U
    }
  } else {
    // A clear finds the cursors clean (cleared behind the last scatter), being cleared behind it
    // (busy until that is done), or, after reset, holding anything: then every word is cleared.
    when(io.clear) { counted := 0.U; scattered := 0.U; bad := false.B }
    when(io.clear && state === S.idle && !clean) {
      state := S.clearing; walk := 0.U; clearTo := (1 << wordsLog2).U
    }.elsewhen(io.scrub.get && state === S.idle) {
      state := S.clearing; walk := 0.U; clearTo := usedWords; clean := false.B
    }.elsewhen(io.prefix && state === S.idle) {
      state := S.summing; walk := 0.U; sum := 0.U; clean := false.B
    }
    when(countFires.asUInt.orR) { clean := false.B }
  }
  when(state === S.clearing) {
    walk := walk + 1.U
    when(walk + 1.U === (if (clearBehind) clearTo else usedWords)) { state := S.idle; clean := true.B }
  }
  when(state === S.summing && walk < sumWords) { walk := walk + 1.U }
  when(sumApply) {
    sum := sum + preEnds.last
    when(sumLast) { state := S.idle }
  }
  // Copies 1 and up hold the ends from the prefix sum on; nothing else writes them.
  private val ends = flat(preEnds.map(sum + _))
  for (t <- if (clearBehind) tables else tables.tail) when(sumApply) { t.write(sumW, ends) }

  // --- count / scatter: a two-stage read-modify-write of one counter per port --------------
  io.in.foreach(_.ready := state === S.idle && !io.clear && !io.prefix)
  for ((t, p) <- cursors.zipWithIndex) {
    val in = io.in(p)
    val inRange = in.bits.bucket < used
    val fire = in.fire && inRange
    when(in.fire && !inRange) { bad := true.B }
    val rd = t.read(wordOf(in.bits.bucket), fire)
    val s1 = RegNext(fire, false.B)
    val s1b = RegEnable(in.bits.bucket, fire)
    val s1scatter = RegEnable(in.bits.scatter, fire)
    val s1item = RegEnable(in.bits.item, fire)
    // The word written the cycle before, for the read that was issued alongside it: whether it
    // is the same word is compared as the read is issued and registered (fwdHit), so the
    // forwarding is a mux, not a compare, ahead of the counter's increment.
    val fwdHit = RegNext(s1 && wordOf(in.bits.bucket) === wordOf(s1b), false.B)
    val fwdV = Reg(UInt((perWord * countW).W))
    val oldWord = lanes(Mux(fwdHit, fwdV, rd))
    // The counter, for the scatter's place: picked from the read word and from the forwarded
    // one apart and then between them (both selects run in parallel from registers and the RAM).
    val old = Mux(fwdHit, lanes(fwdV)(laneOf(s1b)), lanes(rd)(laneOf(s1b)))
    // Every counter of the word incremented in parallel and the bucket's kept: no select of the
    // counter ahead of the increment, which was the sort's slowest path (an adder a counter).
    val newWord = flat((0 until perWord).map(l => Mux(laneOf(s1b) === l.U, oldWord(l) + 1.U, oldWord(l))))
    when(s1) { fwdV := newWord }
    countFires(p) := s1 && !s1scatter
    place(p).valid := s1 && s1scatter
    place(p).bits.pos := old(posW - 1, 0)
    place(p).bits.item := s1item
    // One write port: the read-modify-write, else clear, else the prefix sum's cursor.
    val write = WireDefault(s1)
    val writeW = WireDefault(wordOf(s1b))
    val writeV = WireDefault(newWord)
    when(state === S.clearing) { write := true.B; writeW := walkW; writeV := 0.U }
    when(sumApply) { write := true.B; writeW := sumW; writeV := flat((0 until perWord).map(j => portStart(p, j))) }
    when(write) { t.write(writeW, writeV) }
  }

  // --- each copy: lookups, entries and marks -----------------------------------------------
  for (c <- 0 until copies) {
    val lk = io.lookup(c)
    val prev = lk.bucket - 1.U
    val endRd = lanes(tables(c).read(wordOf(lk.bucket)))
    val beginRd = lanes(tables(c).read(wordOf(prev)))
    val lbZero = RegNext(lk.bucket === 0.U)
    lk.end := endRd(RegNext(laneOf(lk.bucket)))
    lk.word := endRd
    lk.begin := Mux(lbZero, 0.U, beginRd(RegNext(laneOf(prev))))
    val e = entries(c)
    val m = io.mark(c)
    // The write port: the last sort port's placements, or marks (never both: marks come after
    // the scatter). With one sort port that and a read port make a simple dual-port RAM; with
    // two, the other port of a true dual-port RAM places the first port's items or reads.
    val last = place.last
    when(last.valid || m.valid) {
      e.write(Mux(last.valid, last.bits.pos, m.bits.addr), Mux(last.valid, 0.U(1.W), 1.U(1.W)) ## Mux(last.valid, last.bits.item, m.bits.item))
    }
    val entryRd =
      if (ports == 1) e.read(io.entry(c).addr)
      else e.readWrite(Mux(place.head.valid, place.head.bits.pos, io.entry(c).addr), 0.U(1.W) ## place.head.bits.item, true.B, place.head.valid)
    io.entry(c).item := entryRd(itemW - 1, 0)
    io.entry(c).mark := entryRd(itemW)
  }
}

object BucketSort {
  /** The prefix sum's pipeline, from a word's counters read to its cursors written: the ports'
    * totals, a level of the word's prefix a cycle, the offsets within the word. */
  def prefixStages(perWord: Int): Int = 2 + Prefix.levelCount(perWord)

  /** The spans of 2^log2 buckets (counter words, claimed units) that `buckets` fill, at least
    * one: a table smaller than a span still has one. */
  def spans(buckets: UInt, log2: Int): UInt = {
    val w = buckets >> log2
    Mux(w === 0.U, 1.U, w)
  }
}
