package collide.world

import chisel3._
import chisel3.util._
import collide.world.model.BroadPhaseModel

/** The candidate generator of the world-mode broad phase (docs/afu.md, "World mode"), one
  * lane of `lanes`. Over a table sorted by BucketSort it walks its share of the buckets in
  * order (lane l the counter words l, l + lanes, ...; buckets are cells' hashes, so the shares
  * are even on average, and a bucket is never split, so a lane marks only its own entries);
  * in each occupied
  * bucket it takes the cells in order of their first entry, a chunk of up to `chunk` spheres
  * at a time (a scan of the bucket loads the first unmarked entry's cell and marks what it
  * loads); it then streams the chunk's own cell and its 13 half-shell neighbours (a bucket
  * lookup each, issued while the scan still runs) past the ChunkMatcher, and the next chunk's
  * scan follows the last visit without waiting for it to drain; after a bucket's last chunk the
  * walk to the next bucket overlaps its visits too. Last, the large pass: chunks
  * of the large list meet every non-excluded sphere of this lane's slice of the table
  * [largeFrom, largeTo) (the slices of all lanes cover the table once). With two sort
  * `groups` (four sort ports: two sorts, each of half the table) a bucket's entries are group
  * 0's run then group 1's, read and streamed in that order, so every bucket is still in index
  * order and the chunks and pairs are those of one sort. With `coarse`
  * (BroadPhaseParams.coarseChunks) a coarse cell's 8 cells are a group of 8 consecutive
  * buckets: a group whose spheres fit a chunk is scanned as one run and taken a coarse cell at
  * a time (the scan loads the first unmarked entry's coarse cell), each chunk streaming the 43
  * cells some member reaches (BroadPhaseModel.CoarseVisits) past the ChunkMatcher, whose
  * members apply the half-shell rule by their place (with `scanPairs`, the members pair among
  * themselves as the scan loads them and only the 35 cells outside the coarse cell stream,
  * BroadPhaseModel.CoarseOthers); any other group is walked bucket by bucket as without. With
  * one lane the pair stream is exactly BroadPhaseModel.run's candidates, the grid part in
  * the same order, the large part as a set; the lanes' streams together are that set.
  */
class CandidateGeneratorIO(itemW: Int, countW: Int, cellBits: Int, qWidth: Int, bucketsLog2: Int, largeSlots: Int,
                           perWord: Int, lanes: Int, groups: Int, claimW: Int = 0, boxBuckets: Boolean = false) extends Bundle {
  val start = Input(Bool())
  /** With box buckets, the world's box map (CellHash), fixed during the grid. */
  val box = if (boxBuckets) Some(Input(new BoxMapBits(cellBits, bucketsLog2))) else None
  /** This lane's number, 0 until lanes (none with one lane). */
  val lane = if (lanes > 1) Some(Input(UInt(log2Ceil(lanes).W))) else None
  val usedLog2 = Input(UInt(log2Ceil(bucketsLog2 + 1).W))
  /** The buckets the walk covers, a whole number of words (BroadPhaseModel.walkBuckets). */
  val walkBuckets = Input(UInt((bucketsLog2 + 1).W))
  /** With claims (BroadPhase's shared counters): `need` asks for work when the lane has none
    * to walk (so no lane sits on work another could take); `claim` is what was granted, a
    * unit's first bucket or, `single`, one bucket of a deferred unit; taken when `take`. A unit
    * that is not one coarse chunk is not walked but handed back on `defer` (accepted when
    * `deferOk`), to be dealt a bucket at a time; `unresolved` while a unit's word is being read
    * or its deferral waits; `claimsOut` once nothing is left to grant or to come back. */
  val need = if (claimW > 0) Some(Output(Bool())) else None
  val claim = if (claimW > 0) Some(Input(Valid(new Bundle { val bucket = UInt(claimW.W); val single = Bool() }))) else None
  val take = if (claimW > 0) Some(Output(Bool())) else None
  val defer = if (claimW > 0) Some(Valid(UInt(claimW.W))) else None
  val deferOk = if (claimW > 0) Some(Input(Bool())) else None
  val unresolved = if (claimW > 0) Some(Output(Bool())) else None
  val claimsOut = if (claimW > 0) Some(Input(Bool())) else None
  val slack = Input(UInt(qWidth.W))
  val larges = Input(Vec(largeSlots, new WorldKey(itemW, cellBits, qWidth)))
  val largeCount = Input(UInt(log2Ceil(largeSlots + 1).W))
  /** The spheres this lane streams past the large list: [largeFrom, largeTo). */
  val largeFrom = Input(UInt(countW.W))
  val largeTo = Input(UInt(countW.W))
  /** Each group's sorted table (BroadPhaseParams.sortGroups) is looked up at once. */
  val lookup = new Bundle {
    val bucket = Output(UInt(bucketsLog2.W))
    val begin = Input(Vec(groups, UInt(countW.W))) // the cycle after
    val end = Input(Vec(groups, UInt(countW.W)))
    val word = Input(Vec(groups, Vec(perWord, UInt(countW.W)))) // BucketSort's: the ends of bucket's word
  }
  val entry = new Bundle {
    val addr = Output(UInt(itemW.W))
    val group = Output(UInt(StreamRange.groupW(groups).W))
    val item = Input(UInt(itemW.W)) // the cycle after, from group's table
    val mark = Input(Bool())
  }
  val mark = Valid(new Bundle { val group = UInt(StreamRange.groupW(groups).W); val addr = UInt(itemW.W); val item = UInt(itemW.W) })
  val keyAddr = Output(UInt(itemW.W))
  val keyData = Input(new KeyRecord(cellBits, qWidth)) // keyLatency cycles after keyAddr
  val pairs = Decoupled(new WorldPair(itemW))
  val busy = Output(Bool())
  val inLargePass = Output(Bool())
  /** In the grid (walking or in a chunk): what this cycle went to (GridCycle), for the status. */
  val inGrid = Output(Bool())
  val gridCycle = Output(UInt(GridCycle.width.W))
  val stats = Output(new Bundle {
    val cells = UInt(32.W)   // occupied cells visited
    val chunks = UInt(32.W)  // chunks (a cell of more than `chunk` spheres has several)
    val scanned = UInt(32.W) // entries read by the chunk scans
    val probes = UInt(32.W)  // entries streamed past chunks (the 14 visits and the large pass)
  })
}

class CandidateGenerator(itemW: Int, countW: Int, cellBits: Int, qWidth: Int, bucketsLog2: Int, chunk: Int,
                         largeSlots: Int, keyLatency: Int = 1, wordLog2: Int = 0, lanes: Int = 1, groups: Int = 1,
                         coarse: Boolean = false, team: Int = 1, claims: Boolean = false, hitQueue: Int = 0,
                         boxBuckets: Boolean = false, drainBehind: Boolean = false, lookAhead: Int = 3,
                         scanPairs: Boolean = false, nearBits: Int = 0)
    extends Module {
  require(wordLog2 >= 0 && wordLog2 <= bucketsLog2, s"wordLog2 $wordLog2 must be 0..bucketsLog2")
  require(lanes >= 1, s"lanes must be >= 1, got $lanes")
  require(lookAhead >= 3 && lookAhead <= 16, s"lookAhead must be 3..16, got $lookAhead")
  require(!scanPairs || coarse, "scanPairs needs coarse chunks")
  require(Seq(1, 2, 4, 8).contains(groups), s"groups must be 1, 2, 4 or 8, got $groups")
  private val perWord = 1 << wordLog2
  /** Buckets of a coarse cell's group: 8, or a whole word of a table smaller than that. */
  private val groupLog2 = math.min(3, wordLog2)
  /** With coarse chunks, lanes work in teams of `team`: a coarse cell's 8 cells share a word,
    * so dealing whole words would give one lane all of a dense region. Team t walks the words
    * t, t + lanes / team, ...; its member m takes the coarse groups (by group number) and the
    * other groups' buckets (by bucket number) that are m modulo the team. Every member reads
    * every word of its team: the walk is `team` times as long a lane. */
  private val teamSize = if (coarse && !claims) team else 1
  /** With claims, the buckets a claim holds: a coarse group, or a word. */
  private val unitLog2 = CandidateGenerator.unitLog2(wordLog2, coarse)
  require(isPow2(teamSize) && lanes % teamSize == 0, s"a team of $teamSize must be a power of two dividing the lanes ($lanes)")
  private val dealByUnit = teamSize > 1
  private val memberBits = log2Ceil(teamSize)
  private lazy val member: UInt = if (dealByUnit) laneNo(memberBits - 1, 0) else 0.U
  private lazy val teamNo: UInt = if (dealByUnit) (laneNo >> memberBits) else laneNo
  /** Words from one of this lane's words to its next. */
  private val wordStep = lanes / teamSize
  require(!coarse || wordLog2 >= 3 || wordLog2 == bucketsLog2,
    s"coarse chunks need words of 8 counters or one word for the table, got wordLog2 $wordLog2 of $bucketsLog2")
  override def desiredName = s"CandidateGenerator_i${itemW}_b${bucketsLog2}_c${cellBits}_q${qWidth}_k${chunk}_L${largeSlots}_r${keyLatency}_w$wordLog2" +
    (if (lanes > 1) s"_l$lanes" else "") + (if (groups > 1) s"_g$groups" else "") + (if (coarse) s"_x$teamSize" else "") + (if (claims) "_u" else "") +
    (if (hitQueue > 0) s"_h$hitQueue" else "") + (if (boxBuckets) "_bx" else "") + (if (drainBehind) "_d" else "") + (if (lookAhead != 3) s"_a$lookAhead" else "") + (if (scanPairs) "_sp" else "") +
    (if (nearBits > 0) s"_n$nearBits" else "")
  val io = IO(new CandidateGeneratorIO(itemW, countW, cellBits, qWidth, bucketsLog2, largeSlots, perWord, lanes, groups,
    if (claims) CandidateGenerator.claimW(bucketsLog2) else 0, boxBuckets))
  private val laneNo: UInt = io.lane.getOrElse(0.U)

  private val visitT = new WorldVisit(cellBits)
  private val stream = Module(new KeyStream(visitT, itemW, countW, cellBits, qWidth, keyLatency, groups))
  // The large pass loads at most largeSlots members a round (its rounds are of `chunk`, and
  // no more than largeCount), so the matcher's wide slots are the first min(chunk, largeSlots).
  private val matcher = Module(new ChunkMatcher(itemW, cellBits, qWidth, chunk, hitQueue, drainBehind, nearBits, wide = largeSlots))
  io.entry.addr := stream.io.entryAddr
  io.entry.group := stream.io.entryGroup
  stream.io.entryItem := io.entry.item
  stream.io.entryMark := io.entry.mark
  io.keyAddr := stream.io.keyAddr
  stream.io.keyData := io.keyData
  matcher.io.slack := io.slack
  io.pairs <> matcher.io.out

  private object S extends ChiselEnum { val idle, walk, chunk, largeLoad, largeStream = Value }
  private val state = RegInit(S.idle)
  io.busy := state =/= S.idle
  io.inLargePass := state === S.largeLoad || state === S.largeStream
  io.inGrid := state === S.walk || state === S.chunk

  // Defaults: nothing requested, loaded, marked or matched.
  stream.io.req.valid := false.B
  stream.io.req.bits := DontCare
  stream.io.out.ready := false.B
  matcher.io.clear := false.B
  matcher.io.load.valid := false.B
  matcher.io.load.bits := DontCare
  matcher.io.in.valid := false.B
  matcher.io.in.bits := DontCare
  /** Streams the stream's entry into the matcher, the one way all three users do it: a visit's
    * entry goes past the chunk as a probe of the visit's cell (`anyCellOwn` None); the large
    * pass's entries and a coarse chunk's scanned ones (pairs in the scan) meet every member,
    * in any cell, with `own` the matcher's rule for two large spheres (`anyCellOwn`). */
  private def probe(valid: Bool, anyCellOwn: Option[Bool]): Unit = {
    val it = stream.io.out.bits
    matcher.io.in.valid := valid
    matcher.io.in.bits.key := WorldKey(itemW, it.item, it.rec)
    anyCellOwn match {
      case Some(own) => matcher.io.in.bits.anyCell := true.B; matcher.io.in.bits.own := own
      case None =>
        matcher.io.in.bits.anyCell := false.B
        matcher.io.in.bits.cell := it.tag.cell; matcher.io.in.bits.off := it.tag.off
    }
  }
  io.mark.valid := false.B
  io.mark.bits.group := stream.io.out.bits.group
  io.mark.bits.addr := stream.io.out.bits.pos(itemW - 1, 0)
  io.mark.bits.item := stream.io.out.bits.item
  io.lookup.bucket := 0.U

  private val walkEnd = io.walkBuckets // (lookups use all 2^usedLog2 buckets' hash)
  private val cells, chunks, scanned, probes = RegInit(0.U(32.W))
  io.stats.cells := cells; io.stats.chunks := chunks; io.stats.scanned := scanned; io.stats.probes := probes

  // --- bucket walk: a word of buckets a cycle; an occupied bucket stops it -----------------
  // Wide enough for a step of `lanes` words past the last one.
  private val bIssue = Reg(UInt(log2Ceil((1 << bucketsLog2) + lanes * perWord + 1).W))
  private val walkPend = RegInit(false.B)
  // With claims, a word is decoded over two cycles: the cycle its ends come back registers
  // the first occupied bucket, each group's total and that bucket's ends
  // taken either way (the bucket, its group); `walkDec`, the next, decides from registers. A
  // walk step takes a cycle more: a unit's few steps beside its chunk's hundreds of cycles.
  private val walkDec = RegInit(false.B)
  private val walkBusy = walkPend || walkDec
  private val walkB = Reg(UInt((bucketsLog2 + 1).W))
  /** A bucket's word's first bucket, and the bucket's place in it. */
  private def wordBase(b: UInt): UInt = (b >> wordLog2) << wordLog2
  private def wordFrom(b: UInt): UInt = if (wordLog2 == 0) 0.U else b(wordLog2 - 1, 0)
  // With claims: bIssue is a bucket of the unit being walked (else the next unit is the claim's).
  private val inUnit = RegInit(false.B)
  private val single = RegInit(false.B)   // the claim walked is one bucket of a deferred unit
  private val unitFirst = RegInit(false.B) // the lookup pending is a unit's first
  private val deferPend = RegInit(false.B) // the unit at walkB waits to be handed back
  // The word a lookup reads, decoded as the lookup is issued and registered beside walkB, so
  // the cycle its ends come back only finds the first occupied bucket: which buckets lie in
  // the walk (and, with claims, are this lane's), which groups may be taken whole, and the
  // buckets the walk goes on to (the next word of this lane's, the word after this one).
  private val groupsInWord = perWord >> groupLog2
  private val inWalk = Reg(Vec(perWord, Bool()))
  private val mayBeWhole = Reg(Vec(groupsInWord, Bool()))
  private val nextWord = Reg(chiselTypeOf(bIssue)) // base + wordStep words
  private val afterWord = Reg(chiselTypeOf(bIssue)) // base + one word
  io.take.foreach(_ := false.B)
  io.need.foreach(_ := state === S.walk && !inUnit && !walkBusy && !deferPend)
  io.defer.foreach { d => d.valid := deferPend; d.bits := walkB }
  io.unresolved.foreach(_ := (walkBusy && unitFirst) || deferPend)
  io.deferOk.foreach(ok => when(ok) { deferPend := false.B })
  // --- the chunk: its cell, where its scan starts, what the scan found ----------------------
  // Per group: where the scan starts, and the bucket's end (a bucket's entries: group 0's, then 1's).
  private val p = Reg(Vec(groups, UInt(countW.W)))
  private val bEnd = Reg(Vec(groups, UInt(countW.W)))
  // The chunk's base cell: its cell, or its coarse cell's first cell (low bits clear).
  private val curCell = Reg(Vec(3, SInt(cellBits.W)))
  private val coarseCh = RegInit(false.B) // the chunk is a coarse cell's
  private val haveCell = Reg(Bool())
  private val loaded = Reg(UInt(log2Ceil(chunk + 1).W))
  private val moreOfCell = Reg(Bool())
  private val nextSet = Reg(Bool())
  private val nextLeader = Reg(UInt(countW.W))
  private val nextGroup = Reg(UInt(StreamRange.groupW(groups).W))
  private val nextCell = Reg(Vec(3, SInt(cellBits.W)))
  private val sent = Reg(Bool())
  private val scanLeft = Reg(UInt(countW.W))
  private val needClear = Reg(Bool())
  // --- visits: 14 lookups (43 for a coarse chunk, 35 with scanPairs), each a stream range ----
  private val fineVisits = BroadPhaseModel.Visits
  private val coarseVisits =
    if (!coarse) Nil else if (scanPairs) BroadPhaseModel.CoarseOthers else BroadPhaseModel.CoarseVisits
  // A table each, both indexed by vIssue and one picked: no add in front of the look-up.
  private def offsetTable(vs: Seq[(Int, Int, Int)]) = VecInit(vs.map { case (a, b, c) => VecInit(Seq(a, b, c).map(_.S(3.W))) })
  private val fineOffsets = offsetTable(fineVisits)
  private val coarseOffsets = if (coarseVisits.isEmpty) None else Some(offsetTable(coarseVisits))
  private val visitCount = Mux(coarseCh, coarseVisits.length.U, fineVisits.length.U)
  private val vIssue = Reg(UInt(log2Ceil(math.max(fineVisits.length, coarseVisits.length) + 1).W))
  private val lkPend = RegInit(false.B)
  private val lkVisit = Reg(visitT)
  // `lookAhead` ranges: at least three, one for the stream to take each cycle while a lookup
  // is in flight and another is issued (visits of one entry or none follow each other at a
  // cycle each); more let the lookups run ahead through a visit of many entries, for the
  // run of short and empty ones after it (a visit's lookup takes a cycle, empty or not).
  // The visits' lookups run in stages so that no path goes from vIssue through the offsets,
  // the adds and the hash to the table's address: `lkCell` (registered so the hash starts
  // from a register, not from vIssue's offset and the adds) holds the neighbour cell issued
  // the cycle before; CellHash's own registers (`lkHashing`: its latency, a subtraction and
  // a multiply apart) follow; `lkHash` (registered so the address leaving the block comes
  // from a register) holds its bucket, the table's address this cycle; `lkPend` marks the
  // lookup whose ends come back now. Each stage before `lkPend` adds a range in flight, so
  // the queue is as much deeper and the look-ahead check counts them: as many ranges are
  // queued ahead as without them.
  private val lkStages = 2 + CellHash.latency
  private val lkCellV = RegInit(false.B)
  private val lkCell = Reg(visitT)
  private val lkHashing = RegInit(VecInit(Seq.fill(CellHash.latency)(false.B)))
  private val lkHashV = RegInit(false.B)
  private val lkHash = Reg(chiselTypeOf(io.lookup.bucket))
  private val lkHashVisit = Reg(visitT)
  private val lkInFlight = lkCellV.asUInt +& PopCount(lkHashing) +& lkHashV.asUInt +& lkPend.asUInt
  private val lkq = Module(new Queue(new StreamRange(visitT, countW, groups), lookAhead + lkStages))
  lkq.io.enq.valid := false.B
  lkq.io.enq.bits := DontCare
  lkq.io.deq.ready := false.B
  // The ranges issued and not yet taken by the stream or dropped (lkq's count plus lkInFlight),
  // kept in a register of its own: the queue's count (a difference of its pointers) and the
  // additions were a long path into the issue decision and, through vIssue, the offsets.
  private val lkTotal = RegInit(0.U(log2Ceil(lookAhead + lkStages + 2).W))
  private val lkIssue = WireDefault(false.B)
  private val lkDrop = WireDefault(false.B)
  lkTotal := lkTotal + lkIssue.asUInt - lkq.io.deq.fire.asUInt - lkDrop.asUInt
  assert(lkTotal === lkq.io.count +& lkInFlight, "CandidateGenerator: lookups counted apart from the queue and stages")
  // --- large pass ------------------------------------------------------------------------
  // The large pass's next chunk of large spheres starts here, a register of its own: the end of a
  // chunk compares it with the count, no add before the compare.
  private val liNext = Reg(UInt(log2Ceil(largeSlots + 2 * chunk + 1).W))
  private val lj = Reg(UInt(log2Ceil(chunk + 1).W))
  private val lIdx = Reg(UInt(log2Ceil(largeSlots + chunk + 1).W)) // the chunk's first plus lj, kept so no add lies before the large list's read
  private val lLoad = RegInit(false.B) // lKey was read last cycle: the matcher loads it now
  private val lKey = Reg(new WorldKey(itemW, cellBits, qWidth))
  lLoad := false.B
  when(lLoad) { matcher.io.load.valid := true.B }

  /** A chunk of a new bucket: its scan is requested behind the last chunk's visits, and its
    * first scan entry clears the matcher once their hits have left. */
  private def startChunk(): Unit = {
    state := S.chunk; sent := false.B; vIssue := 0.U; lkPend := false.B; needClear := true.B
    lkCellV := false.B; lkHashing.foreach(_ := false.B); lkHashV := false.B
  }
  private def startLargePass(): Unit = {
    liNext := chunk.U; lj := 0.U; lIdx := 0.U; matcher.io.clear := true.B
    state := Mux(io.largeCount === 0.U || io.largeFrom >= io.largeTo, S.idle, S.largeLoad)
  }

  switch(state) {
    is(S.idle) {
      when(io.start) {
        state := S.walk; bIssue := teamNo << wordLog2; walkPend := false.B; inUnit := false.B; deferPend := false.B
        cells := 0.U; chunks := 0.U; scanned := 0.U; probes := 0.U
      }
    }
    is(S.walk) {
      // A word of buckets a cycle: the lookup of bIssue returns the ends of its whole word,
      // and the first occupied bucket of this lane's at or after bIssue starts a chunk; none,
      // this lane's next word.
      // With claims, a lookup only while none is pending (its word may end the unit, or not),
      // of the unit's next bucket or else of the held claim's first, which it takes.
      val claimV = io.claim.map(_.valid).getOrElse(false.B)
      val issueOk = if (claims) !walkBusy && !deferPend && (inUnit || claimV) else bIssue < walkEnd
      val issueAt = if (claims) Mux(inUnit, bIssue, io.claim.get.bits.bucket) else bIssue
      io.lookup.bucket := issueAt(math.max(1, bucketsLog2) - 1, 0)
      walkPend := issueOk
      // The claim's single flag as the word is read (its first word sets it).
      val singleAt = if (claims) Mux(issueOk && !inUnit, io.claim.get.bits.single, single) else single
      when(issueOk || (!claims).B) {
        walkB := issueAt
        val (b, f) = (wordBase(issueAt), wordFrom(issueAt))
        // With claims, a lane takes the buckets of its claim: one, or the unit's.
        def claimed(l: Int): Bool =
          if (!claims) true.B
          else Mux(singleAt, f === l.U, if (unitLog2 >= wordLog2) true.B else (f >> unitLog2) === (l >> unitLog2).U)
        // b + l < walkEnd with b a word's first bucket: the word before walkEnd's, or walkEnd's
        // own word below its offset; a word-index compare, not an adder and compare a bucket.
        val (wordNo, endNo) = (issueAt >> wordLog2, walkEnd >> wordLog2)
        val (before, atEnd) = (wordNo < endNo, wordNo === endNo)
        for (l <- 0 until perWord) inWalk(l) := l.U >= f && (before || atEnd && l.U < wordFrom(walkEnd)) && claimed(l)
        // A walk resumed inside a group (from > its first bucket) follows a bucket of it taken
        // cell by cell: that group is not taken whole (and its first begin is not in the word read).
        for (gi <- 0 until groupsInWord) mayBeWhole(gi) := coarse.B && f <= (gi << groupLog2).U && !singleAt
        nextWord := b + (wordStep * perWord).U
        afterWord := b + perWord.U
      }
      when(issueOk) {
        if (claims) {
          inUnit := false.B; io.take.get := !inUnit; unitFirst := !inUnit && !io.claim.get.bits.single
          when(!inUnit) { single := io.claim.get.bits.single }
        } else bIssue := ((bIssue >> wordLog2) + wordStep.U) << wordLog2
      }
      val base = wordBase(walkB)
      /** Bucket k < perWord of the word read: base + k, no carry past the word. */
      def inWord(k: UInt): UInt = if (wordLog2 == 0) base else Cat(base >> wordLog2, k(wordLog2 - 1, 0))
      val ends = io.lookup.word
      // Bucket 0's begin is right when walkB is the word's first bucket.
      val begins = (0 until groups).map(g => VecInit(io.lookup.begin(g) +: ends(g).init))
      // With coarse chunks, each group of 8 buckets: taken whole if its spheres fit a chunk.
      val totals = VecInit((0 until groupsInWord).map { gi =>
        val (lo, last) = (gi << groupLog2, ((gi + 1) << groupLog2) - 1)
        (0 until groups).map(g => ends(g)(last) - begins(g)(lo)).reduce(_ +& _)
      })
      val gCoarse = VecInit((0 until groupsInWord).map(gi => mayBeWhole(gi) && totals(gi) <= chunk.U))
      // In a team, a member takes the coarse groups and the other groups' buckets whose number
      // among the team's is its own modulo the team: a group by its number in the team's walk
      // (word number over the teams, then the group in the word), a bucket by its place in the word.
      def mine(l: Int): Bool =
        if (!dealByUnit) true.B
        else {
          val walkWord = base >> (wordLog2 + log2Ceil(wordStep))
          val walkGroup = if (wordLog2 == groupLog2) walkWord else Cat(walkWord, (l >> groupLog2).U((wordLog2 - groupLog2).W))
          val bucket = inWord(l.U(math.max(1, wordLog2).W)).pad(memberBits)
          Mux(gCoarse(l >> groupLog2), walkGroup.pad(memberBits)(memberBits - 1, 0), bucket(memberBits - 1, 0)) === member
        }
      val occupied = VecInit((0 until perWord).map(l => inWalk(l) && mine(l) &&
        (0 until groups).map(g => ends(g)(l) =/= begins(g)(l)).reduce(_ || _)))
      val firstLane = PriorityEncoder(occupied.asUInt)
      def groupLo(l: UInt): UInt = (l >> groupLog2) << groupLog2
      def groupLast(l: UInt): UInt = groupLo(l) | ((1 << groupLog2) - 1).U
      // The first occupied bucket's ends, taken as a bucket and as its group.
      def bucketEnds(l: UInt) = (0 until groups).map(g => (begins(g)(l), ends(g)(l)))
      def groupEnds(l: UInt) = (0 until groups).map(g => (begins(g)(groupLo(l)), ends(g)(groupLast(l))))
      val (decided, anyOccupied, lane, asCoarse, asBucket, asGroup) =
        if (!claims) (walkPend, occupied.asUInt.orR, firstLane, gCoarse(firstLane >> groupLog2),
          bucketEnds(firstLane), groupEnds(firstLane))
        else {
          val decAny = Reg(Bool())
          val decLane = Reg(chiselTypeOf(firstLane))
          val decTotals = Reg(chiselTypeOf(totals)) // compared with the chunk in the deciding cycle
          val decBucket, decGroup = Reg(Vec(groups, Vec(2, UInt(countW.W))))
          walkDec := walkPend
          when(walkPend) {
            decAny := occupied.asUInt.orR; decLane := firstLane; decTotals := totals
            for ((d, e) <- Seq(decBucket -> bucketEnds(firstLane), decGroup -> groupEnds(firstLane)); g <- 0 until groups) {
              d(g)(0) := e(g)._1; d(g)(1) := e(g)._2
            }
          }
          val g = decLane >> groupLog2
          (walkDec, decAny, decLane, mayBeWhole(g) && decTotals(g) <= chunk.U, decBucket.map(v => (v(0), v(1))),
            decGroup.map(v => (v(0), v(1))))
        }
      val gLast = groupLast(lane)
      val lastInWord = (perWord - 1).U
      // A unit's first word whose group is not one coarse chunk goes back to be dealt a bucket at a time.
      val deferIt = (claims && coarse).B && unitFirst && !asCoarse
      when(decided && anyOccupied && deferIt) {
        deferPend := true.B; walkPend := false.B
      }.elsewhen(decided && anyOccupied) {
        when(asCoarse) {
          for (g <- 0 until groups) { p(g) := asGroup(g)._1; bEnd(g) := asGroup(g)._2 }
          bIssue := Mux(gLast === lastInWord, nextWord, inWord(gLast + 1.U))
        }.otherwise {
          for (g <- 0 until groups) { p(g) := asBucket(g)._1; bEnd(g) := asBucket(g)._2 }
          // On past it in this word, or at the word's end on to this lane's next word.
          bIssue := Mux(lane === lastInWord, nextWord, inWord(lane + 1.U))
        }
        if (claims) {
          // Past the bucket; the unit goes on unless that was its last bucket (a coarse group is one unit).
          val lastOfUnit = if (unitLog2 == 0) true.B else lane(unitLog2 - 1, 0).andR
          inUnit := !asCoarse && !lastOfUnit && !single
          bIssue := Mux(lane === lastInWord, afterWord, inWord(lane + 1.U))
        }
        coarseCh := asCoarse
        haveCell := false.B
        walkPend := false.B; cells := cells + 1.U
        startChunk()
      }.elsewhen(!walkBusy && !issueOk && !deferPend && io.claimsOut.getOrElse(true.B) && stream.io.idle && matcher.io.idle) {
        startLargePass() // the last chunk's visits all matched
      }
    }
    is(S.chunk) {
      // The scan's range first, then the 14 visits' ranges, all through the one stream: the
      // visits' lookups start as soon as the chunk's cell is known, while the scan runs.
      stream.io.req.valid := !sent
      stream.io.req.bits.begin := p; stream.io.req.bits.end := bEnd
      stream.io.req.bits.direct := false.B
      stream.io.req.bits.tag := 0.U.asTypeOf(visitT)
      stream.io.req.bits.tag.scan := true.B
      when(sent) { stream.io.req <> lkq.io.deq }
      when(stream.io.req.fire && !sent) {
        sent := true.B; nextSet := false.B; moreOfCell := false.B; loaded := 0.U
        scanLeft := (0 until groups).map(g => bEnd(g) - p(g)).reduce(_ + _)
        chunks := chunks + 1.U
      }

      // AND-OR selects from vIssue's one-hot, not a table look-up: a look-up whose result is
      // registered (lkCell.off) becomes a ROM whose address register is vIssue's next value,
      // which puts the whole issue decision in front of the ROM.
      def pick(t: Vec[Vec[SInt]]) = Mux1H(UIntToOH(vIssue, t.length).asBools, t)
      val fine = pick(fineOffsets)
      val off = coarseOffsets.fold(fine)(t => Mux(coarseCh, pick(t), fine))
      val nc = VecInit((0 until 3).map(a => curCell(a) + off(a)))
      // Every range in flight may end up queued: issue only while the queue has room for them all.
      val canIssue = haveCell && vIssue =/= visitCount && lkTotal < (lookAhead + lkStages).U
      lkIssue := canIssue
      when(canIssue) { vIssue := vIssue + 1.U }
      // Stage 1: the neighbour cell and its offset.
      lkCellV := canIssue
      lkCell.cell := nc; lkCell.off := off; lkCell.scan := false.B
      // Stage 2: its bucket, CellHash.latency cycles after the registered cell.
      for (k <- 0 until CellHash.latency) lkHashing(k) := (if (k == 0) lkCellV else lkHashing(k - 1))
      lkHashV := lkHashing.last
      lkHash := CellHash(lkCell.cell, bucketsLog2, io.usedLog2, coarse, io.box)
      lkHashVisit := ShiftRegister(lkCell, CellHash.latency)
      // Stage 3: the registered bucket is the table's address; its ends come back the cycle after.
      io.lookup.bucket := lkHash
      lkPend := lkHashV
      lkVisit := lkHashVisit
      // A visit whose bucket is empty in every group is not queued: the stream would spend a
      // cycle accepting it, and a uniform cloud's coarse chunk has a dozen of its 43 visits empty.
      val lkEmpty = (0 until groups).map(g => io.lookup.begin(g) === io.lookup.end(g)).reduce(_ && _)
      lkq.io.enq.valid := lkPend && !lkEmpty
      lkDrop := lkPend && lkEmpty
      lkq.io.enq.bits.begin := io.lookup.begin; lkq.io.enq.bits.end := io.lookup.end
      lkq.io.enq.bits.direct := false.B; lkq.io.enq.bits.tag := lkVisit

      // Every range handed to the stream and the scan's entries all seen: the next chunk of
      // this bucket can start its scan behind the visits still streaming.
      val visitsIssued = vIssue === visitCount && !lkCellV && !lkHashing.asUInt.orR && !lkHashV && !lkPend && !lkq.io.deq.valid
      val scanDone = sent && scanLeft === 0.U
      when(visitsIssued && scanDone) {
        when(moreOfCell || nextSet) {
          sent := false.B; vIssue := 0.U; needClear := true.B
          // The next cell is known already: its visits' lookups need not wait for its scan.
          when(!moreOfCell) {
            // Scans go in group order: a leader in group g leaves nothing of the groups before it to scan.
            if (groups == 1) p(0) := nextLeader
            else for (g <- 0 until groups) {
              when(g.U < nextGroup) { p(g) := bEnd(g) }.elsewhen(g.U === nextGroup) { p(g) := nextLeader }
            }
            curCell := nextCell; haveCell := true.B; cells := cells + 1.U
          }
        }.otherwise {
          // On to the next bucket while this chunk's visits still stream: the walk's lookups
          // and the next scan's reads overlap them; its first scan entry waits for the
          // matcher as above.
          state := S.walk; walkPend := false.B // bIssue is already the next bucket
        }
      }
    }
    is(S.largeLoad) {
      // A large key is read into lKey and loaded the cycle after (the list's mux and the box's
      // additions each take a cycle); the stream starts once the last one is in.
      when(lj =/= chunk.U && lIdx < io.largeCount) {
        lLoad := true.B; lKey := io.larges(VecIndex(lIdx, largeSlots))
        lj := lj + 1.U; lIdx := lIdx + 1.U
      }.elsewhen(!lLoad) {
        state := S.largeStream; sent := false.B
      }
    }
    is(S.largeStream) {
      stream.io.req.valid := !sent
      stream.io.req.bits.begin := VecInit(io.largeFrom +: Seq.fill(groups - 1)(0.U(countW.W)))
      stream.io.req.bits.end := VecInit(io.largeTo +: Seq.fill(groups - 1)(0.U(countW.W)))
      stream.io.req.bits.direct := true.B; stream.io.req.bits.tag := DontCare
      when(stream.io.req.fire) { sent := true.B }
      val it = stream.io.out.bits
      probe(stream.io.out.valid && !it.rec.excluded, anyCellOwn = Some(it.rec.large)) // two large spheres meet once: from the lower
      stream.io.out.ready := matcher.io.in.ready || it.rec.excluded
      when(stream.io.out.fire && !it.rec.excluded) { probes := probes + 1.U }
      when(sent && stream.io.idle && matcher.io.idle) {
        liNext := liNext + chunk.U; lj := 0.U; lIdx := liNext; matcher.io.clear := true.B
        state := Mux(liNext < io.largeCount, S.largeLoad, S.idle)
      }
    }
  }
  // The stream's entries in the grid: scan entries (chunk state only) load the chunk, visits'
  // entries go past it, also while the walk looks for the next bucket.
  when(state === S.chunk || state === S.walk) {
    val it = stream.io.out.bits
    when(it.tag.scan) {
      // A coarse chunk's cells are those of its base's coarse cell: compared with low bits clear.
      val base = VecInit(it.rec.cell.map(c => Mux(coarseCh, Cat(c(cellBits - 1, 1), 0.U(1.W)).asSInt, c)))
      val same = base.asUInt === curCell.asUInt
      val take = !it.mark && (!haveCell || (same && loaded =/= chunk.U))
      // With scanPairs, an entry a coarse chunk takes also meets the members loaded before it
      // (the matcher's registers hold exactly those), in any cell: all of a coarse cell are
      // neighbours. Not at the clear, whose cycle still holds the last chunk's members (the
      // first entry taken has none before it anyway).
      val pairIt = scanPairs.B && coarseCh && take && !needClear
      if (scanPairs) probe(stream.io.out.valid && pairIt, anyCellOwn = Some(false.B))
      // A chunk's first scan entry waits until the last chunk's hits have all left (they
      // read its members; with drainBehind, only the hits of the chunk before it), then
      // clears the matcher, loading in the same cycle.
      stream.io.out.ready := (!needClear || matcher.io.canClear) && (!pairIt || matcher.io.in.ready)
      when(stream.io.out.fire) {
        scanned := scanned + 1.U
        scanLeft := scanLeft - 1.U
        when(needClear) { matcher.io.clear := true.B; needClear := false.B }
        when(take) {
          matcher.io.load.valid := true.B
          io.mark.valid := true.B
          loaded := loaded + 1.U
          when(!haveCell) { curCell := base; haveCell := true.B }
        }
        when(!it.mark && haveCell && same && loaded === chunk.U) { moreOfCell := true.B }
        when(!it.mark && haveCell && !same && !nextSet) {
          nextLeader := it.pos; nextGroup := it.group; nextCell := base; nextSet := true.B
        }
      }
    }.otherwise {
      probe(stream.io.out.valid, anyCellOwn = None)
      stream.io.out.ready := matcher.io.in.ready
      when(stream.io.out.fire) { probes := probes + 1.U }
    }
  }

  // What the matcher loads: a large sphere in the large pass, else the stream's entry (a scan
  // entry, at its place in a coarse chunk), chosen by the state alone, so that the members'
  // box additions do not wait on the scan's take (the stream's ready and the compares).
  {
    val it = stream.io.out.bits
    val place = Mux(coarseCh, Cat(it.rec.cell(0)(0), it.rec.cell(1)(0), it.rec.cell(2)(0)), 0.U)
    matcher.io.load.bits := Mux(state === S.largeLoad,
      ChunkMember(lKey, 0.U), ChunkMember(WorldKey(itemW, it.item, it.rec), place))
  }

  // What each grid cycle went to: an entry through the stream, or why none went.
  private val outV = stream.io.out.valid
  private val walkDone =
    if (claims) !inUnit && !walkBusy && !deferPend && io.claimsOut.get else !walkPend && bIssue >= walkEnd
  io.gridCycle := MuxCase(GridCycle.walk, Seq(
    stream.io.out.fire -> GridCycle.streamed,
    (outV && stream.io.out.bits.tag.scan && needClear) -> GridCycle.clearWait,
    outV -> GridCycle.hitsFull,
    (state === S.chunk && !haveCell) -> GridCycle.scanStart,
    (state === S.chunk) -> GridCycle.lookups,
    walkDone -> GridCycle.done))
}

/** What a lane's grid cycle went to (BroadPhaseStatus.laneCycles): an entry scanned or streamed
  * past its chunk; an entry held because the matcher's hit queue is full, or because a new
  * chunk's first entry waits for hits still owed; no entry, the chunk's first scan entry not
  * out yet (its reads' latency) or, the chunk known, the visits' lookups and reads behind; the
  * walk to the next bucket or claim; nothing left (other lanes still walk). */
object GridCycle {
  /** The classes in status order; each code is its place here. */
  val names: Seq[String] = Seq("streamed", "hitsFull", "clearWait", "scanStart", "lookups", "walk", "done")
  val width: Int = log2Ceil(names.length)
  private def code(name: String): UInt = { require(names.contains(name), name); names.indexOf(name).U(width.W) }
  val streamed = code("streamed"); val hitsFull = code("hitsFull"); val clearWait = code("clearWait")
  val scanStart = code("scanStart"); val lookups = code("lookups"); val walk = code("walk"); val done = code("done")
}

object CandidateGenerator {
  /** log2 of the buckets a claimed unit holds: a coarse group of 8 (or the word, if smaller),
    * or a word without coarse chunks; a bucket is never split between lanes either way. */
  def unitLog2(wordLog2: Int, coarse: Boolean): Int = if (coarse) math.min(3, wordLog2) else wordLog2
  /** Bits of a claimed bucket (the table's buckets, and one more). */
  def claimW(bucketsLog2: Int): Int = bucketsLog2 + 1
}
