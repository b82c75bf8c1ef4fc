package collide.world

/** What the world-mode broad phase supports (docs/afu.md, "World mode: the broad phase").
  *
  * The broad phase sorts spheres into a uniform grid of cubic cells of edge 2^k and pairs
  * spheres in neighbouring cells; a few "large" spheres, too big for the chosen cell, are
  * paired with every sphere instead. Everything here is exact integer arithmetic on the
  * SCPU's own (converted) values, so it is conservative by construction: see
  * [[collide.world.model.BroadPhaseModel]].
  *
  * @param largeMax   spheres the large list holds: k is chosen so that at most this many
  *                   spheres are large (each costs a pass over the table)
  * @param cellBits   signed width of one cell coordinate; k grows until every sphere's cell
  *                   fits with a one-cell guard on each side (so a neighbour never wraps)
  * @param bucketsLog2 cells hash into 2^bucketsLog2 buckets (a counting sort fills them);
  *                   collisions cost scanning time, never a wrong or duplicate pair
  * @param marginNum  the cell must be at least 2r * marginNum / marginDen for every small
  * @param marginDen  sphere: 9/8 covers every SCPU configuration's hit band (4 ulps, 3% in
  *                   bf16) plus the absolute-error allowance, see BroadPhaseModel
  * @param cellOverError the cell is at least 2^cellOverError times the SCPU's absolute error
  *                   bound (squares that underflow: about sqrt(2^minExp) of the compute format)
  * @param filterFracBits the box filter's fixed point: 2^-filterFracBits of a cell
  * @param chunk      spheres of one cell a candidate generator holds at once (its
  *                   comparators); a fuller cell is visited once per chunk
  * @param wordLog2   the sort's counters sit 2^wordLog2 to a RAM word: clear, prefix sum
  *                   and the generator's walk over the buckets take a word a cycle
  * @param lanes      candidate generators working at once: lane l walks the counter words
  *                   w = l mod lanes and streams its lanes-th slice of the table past the
  *                   whole large list;
  *                   each lane has its own copy of the sort's RAM (it marks its own buckets'
  *                   entries) and its own read port on the sphere table
  * @param bucketsPerSphereLog2 a world of N spheres uses the least power of two of buckets at
  *                   least N * 2^this (at most 2^bucketsLog2): 1 (2N, the default) keeps
  *                   collisions rare; 0 (N) halves the clear, the prefix sum, the walk and the
  *                   counters' RAM for more cells sharing a bucket (scanning time, never a pair)
  * @param sortPorts  spheres a cycle in the sort's passes (1, 2, 4, 8 or 16, at most `lanes`): port
  *                   q reads the q-th part of the table through lane q's sphere port, counting
  *                   and scattering through a port of its own. Two ports share one sort (the
  *                   entries' two block-RAM ports; one more table of counters); four are two
  *                   sorts of two ports (`sortGroups`), each of half the table, whose buckets
  *                   the generators read one after the other (a second table of counters a
  *                   lane); eight are four sorts of two, each of a quarter of the table, and
  *                   16 eight sorts of two, each of an eighth
  * @param cellSteps  cell edges an octave: 1 (the default), powers of two only (2^k, a shift
  *                   of the coordinates); 2, also 1.5 * 2^k (a shift and an exact division by
  *                   three), so no cell is more than 4/3 of what its spheres need instead of
  *                   twice it (a level L: edge 2^(L/2) for even L, 1.5 * 2^((L-1)/2) for odd L).
  *                   Smaller cells pay off where cells overfill a chunk (dense clusters), and
  *                   cost chunks where they are sparse (docs/afu.md, "Cell steps")
  * @param coarseChunks the grid's next step: a cell's bucket is its coarse cell's hash (2 x 2 x 2
  *                   cells) times 8 plus its place in it, so a coarse cell is a group of 8
  *                   consecutive buckets; a group whose spheres fit a chunk is taken one coarse
  *                   cell at a time, a chunk streaming the 43 cells in some member's own or
  *                   half-shell neighbourhood past it, each member applying the half-shell rule
  *                   itself; any other group is chunked cell by cell as without (docs/afu.md,
  *                   "Coarse chunks"). The same candidates, fewer probes. Needs words of at
  *                   least 8 counters (wordLog2 >= 3): the walk reads a group at once
  * @param team       with coarse chunks, lanes that share a walk over the same words, each
  *                   taking its share of their coarse groups and buckets (1: a lane takes whole
  *                   words, so a dense coarse cell's 8 cells are one lane's work; `lanes`: every
  *                   lane walks every word). A power of two; the teams are of `teamSize`
  * @param claims     lanes claim the next unit of buckets (a coarse group of 8, or a word)
  *                   from a shared counter whenever they need one, instead of walking a fixed
  *                   share: a lane that drew dense units takes fewer, so the lanes finish
  *                   together (docs/afu.md, "Claimed work"). Teams are then not used
  * @param hitQueue   streamed spheres with hits a lane's ChunkMatcher queues (0..16) while
  *                   its hits leave one a cycle: the stream goes on instead of stalling for a
  *                   sphere with several hits (docs/afu.md, "Queued hits and 32 counters a word"); 0, it stalls
  * @param boxBuckets a cell's bucket (a coarse cell's group with coarse chunks) is its place in
  *                   the world's box padded by a unit (x first), modulo the table: where the
  *                   padded box's places fit the table no two cells share a bucket (no probe
  *                   wasted on another cell's entries), and the prefix sum and the walk stop at
  *                   the last place (docs/afu.md, "Box buckets", "The padded box"). The box is
  *                   the least and greatest coordinate of every eligible sphere, kept as the
  *                   table arrives; without, Teschner's hash
  * @param drainBehind a lane's ChunkMatcher keeps its members' indices in two banks, so the next
  *                   chunk loads while the last chunk's hits still leave, instead of waiting for
  *                   them (docs/afu.md, "Where a lane's grid cycles go")
  * @param lookAhead  visits' bucket ranges (3..16) a lane looks up ahead of its stream: a
  *                   visit's lookup takes a cycle, so more let the lookups run ahead through
  *                   visits of many entries for the empty and one-entry ones after them
  *                   (docs/afu.md, "Where a lane's grid cycles go")
  * @param scanPairs  with coarse chunks, a coarse chunk's members pair with one another as its
  *                   scan loads them (any two spheres of a coarse cell are in neighbouring
  *                   cells), so its own 8 cells are not visited: 35 visits instead of 43, and
  *                   its members stream once, not twice (docs/afu.md, "Pairs in the scan")
  * @param clearBehind the sort's counters are cleared behind its scatter, while the grid reads
  *                   the bucket ends from tables of their own (one table of counters more a
  *                   sort), so the next world's clear costs no cycle after the grid (docs/afu.md,
  *                   "Starting ahead")
  * @param nearFilter a chunk's slots past the large pass's (the first min(chunk, largeMax))
  *                   compare the box filter modulo 2^(filterFracBits + 4) instead of on the
  *                   whole fixed point: the grid's probes are in cells next to the members', so
  *                   the filter's differences are small and their signs exact modulo that
  *                   (ChunkMatcher.nearBits). The same candidates, about half the comparators'
  *                   cells; false keeps every slot's filter whole (docs/afu.md, "The near filter")
  */
final case class BroadPhaseParams(
    largeMax: Int = 16,
    cellBits: Int = 20,
    bucketsLog2: Int = 17,
    marginNum: Int = 9,
    marginDen: Int = 8,
    cellOverError: Int = 5,
    filterFracBits: Int = 8,
    chunk: Int = 16,
    wordLog2: Int = 3,
    lanes: Int = 1,
    sortPorts: Int = 1,
    bucketsPerSphereLog2: Int = 1,
    cellSteps: Int = 1,
    coarseChunks: Boolean = false,
    team: Int = 4,
    claims: Boolean = false,
    hitQueue: Int = 0,
    boxBuckets: Boolean = false,
    drainBehind: Boolean = false,
    lookAhead: Int = 3,
    scanPairs: Boolean = false,
    clearBehind: Boolean = false,
    nearFilter: Boolean = true
) {
  require(largeMax >= 0 && largeMax <= 4096, s"largeMax must be 0..4096, got $largeMax")
  require(cellBits >= 4 && cellBits <= 30, s"cellBits must be 4..30, got $cellBits")
  require(bucketsLog2 >= 0 && bucketsLog2 <= 24, s"bucketsLog2 must be 0..24, got $bucketsLog2")
  require(marginDen > 0 && marginNum >= marginDen, s"margin $marginNum/$marginDen must be >= 1")
  require(cellOverError >= 5, s"cellOverError must be >= 5 (the margin's proof needs 1/32), got $cellOverError")
  require(filterFracBits >= 0 && filterFracBits <= 24, s"filterFracBits must be 0..24, got $filterFracBits")
  require(chunk >= 1 && chunk <= 256, s"chunk must be 1..256, got $chunk")
  require(wordLog2 >= 0 && wordLog2 <= 5, s"wordLog2 must be 0..5, got $wordLog2")
  require(lanes >= 1 && lanes <= 32, s"lanes must be 1..32 (twice the 16 candidates a pair line holds: past 16, lanes wait their turn for a line), got $lanes")

  require(BroadPhaseParams.sortPortChoices.contains(sortPorts),
    s"sortPorts must be 1, 2, 4, 8 or 16 (a block RAM's two ports, or two, four or eight sorts of two), got $sortPorts")
  require(sortPorts <= lanes, s"sortPorts ($sortPorts) must be at most lanes ($lanes): port p reads the table through lane p's port")

  require(bucketsPerSphereLog2 >= 0 && bucketsPerSphereLog2 <= 2, s"bucketsPerSphereLog2 must be 0..2, got $bucketsPerSphereLog2")

  require(cellSteps == 1 || cellSteps == 2, s"cellSteps must be 1 (edges 2^k) or 2 (also 1.5 * 2^k), got $cellSteps")
  require(!coarseChunks || wordLog2 >= 3,
    s"coarseChunks needs wordLog2 >= 3 (the walk reads a coarse cell's 8 buckets in one word), got wordLog2 $wordLog2")
  require(team >= 1 && chisel3.util.isPow2(team), s"team must be a power of two, got $team")
  require(!scanPairs || coarseChunks, "scanPairs needs coarseChunks (the pairs of a coarse chunk's members)")
  require(lookAhead >= 3 && lookAhead <= 16, s"lookAhead must be 3..16 (visits' ranges a lane looks up ahead of its stream), got $lookAhead")
  require(hitQueue >= 0 && hitQueue <= 16, s"hitQueue must be 0..16 (streamed spheres with hits a lane queues), got $hitQueue")
  /** Lanes a team has: with coarse chunks the largest power of two up to `team` that divides
    * the lanes (1 for an odd lane count: whole words a lane); 1 without, or with claims. */
  val teamSize: Int = if (!coarseChunks || claims) 1 else Iterator.iterate(team)(_ / 2).find(t => lanes % t == 0).get

  val buckets: Int = 1 << bucketsLog2

  /** Buckets the sort's table holds for a table of `maxSpheres`: the cap, and no more than
    * maxSpheres 2^bucketsPerSphereLog2 can use. */
  def tableLog2(maxSpheres: Int): Int =
    math.min(bucketsLog2, math.max(1, chisel3.util.log2Ceil(maxSpheres.toLong << bucketsPerSphereLog2)))
  /** The broad phase's RAMs for `maxSpheres`, a sort's (BucketSort) times the sorts: per lane a
    * table of bucket counters (a word of 2^wordLog2 counters a cycle) and a table of entries (a
    * sphere index and a mark each); a table of counters more per sort port past the first, and
    * one more a sort with clearBehind. Counters take one write and one read a cycle; entries
    * take both ports' scatter writes with two ports a sort. The sphere table it reads is the
    * AFU's (which holds ceil(lanes / 2) more copies for it: two lanes share a copy's two ports). */
  def rams(maxSpheres: Int): Seq[BroadPhaseParams.Ram] = {
    val cap = groupCapacity(maxSpheres)
    val countW = chisel3.util.log2Ceil(cap + 1)
    val itemW = chisel3.util.log2Ceil(maxSpheres)
    val tLog2 = tableLog2(maxSpheres)
    val perWordLog2 = math.min(wordLog2, tLog2)
    Seq(
      BroadPhaseParams.Ram("counters", sortGroups * (lanes + portsPerSort - 1 + (if (clearBehind) 1 else 0)),
        1L << (tLog2 - perWordLog2), (1 << perWordLog2) * countW, twoWrites = false),
      BroadPhaseParams.Ram("entries", sortGroups * lanes, cap.toLong, itemW + 1, twoWrites = portsPerSort == 2))
  }
  /** RAM bits of the broad phase for `maxSpheres` (all of `rams`). */
  def ramBits(maxSpheres: Int): Long = rams(maxSpheres).map(_.bits).sum
  /** Sorts the passes use: one, or with four, eight or 16 ports two, four or eight of two ports, group g
    * sorting the g-th half, quarter or eighth of the table (block RAM has two ports; the generators read
    * every group's buckets). */
  val sortGroups: Int = if (sortPorts >= 4) sortPorts / 2 else 1
  /** Ports of each of those sorts (1 or 2: a block RAM's ports). */
  val portsPerSort: Int = sortPorts / sortGroups
  /** Entries of one group's sorted table: its part of the table, or all of it. */
  def groupCapacity(maxSpheres: Int): Int = (maxSpheres + sortGroups - 1) / sortGroups
  /** Copies of the sphere table the lanes read: two lanes a copy (a block RAM's two ports). */
  val sphereCopies: Int = (lanes + 1) / 2

  /** log2 of a bound on an SCPU's absolute error in d in compute format p: squares that
    * underflow or flush lose at most 3 * 2^minExp of d^2, so at most sqrt(3 * 2^minExp) <
    * 2^errorExp of d. */
  def errorExp(p: collide.fp.FpParams): Int = Math.floorDiv(p.format.minExp, 2) + 2
  /** The smallest cell exponent: the cell is 2^cellOverError times that error. */
  def kFloor(p: collide.fp.FpParams): Int = errorExp(p) + cellOverError
  /** The smallest cell level: an edge of 2^kFloor. */
  def levelFloor(p: collide.fp.FpParams): Int = 2 * kFloor(p)
  /** k >= top - kCoordOffset keeps every cell coordinate of values below 2^top in range. */
  val kCoordOffset: Int = cellBits - 2
  /** The same for levels: level >= 2 top - levelCoordOffset. An edge of 1.5 * 2^(k-1) (level
    * 2k - 1) keeps |v| / edge below 2^(cellBits-1) * 2/3, inside the guard too. */
  val levelCoordOffset: Int = 2 * kCoordOffset + (if (cellSteps == 2) 1 else 0)
  /** Largest cell coordinate magnitude allowed, leaving one cell of guard to the wrap. */
  val cellLimit: Long = (1L << (cellBits - 1)) - 2
}

object BroadPhaseParams {
  /** `count` RAMs of `words` words of `width` bits; `twoWrites`: both ports write in a cycle (a
    * true dual-port block RAM), else one writes and one reads. */
  final case class Ram(what: String, count: Int, words: Long, width: Int, twoWrites: Boolean) {
    def bits: Long = count * words * width
  }
  /** The box filter's exponent of level L: ceil(L / 2), the octave the edge lies in. */
  def filterExp(level: Int): Int = Math.floorDiv(level + 1, 2)
  /** The exact edge of level L as a double (for reports). */
  def edge(level: Int): Double =
    if ((level & 1) == 0) math.scalb(1.0, level / 2) else 1.5 * math.scalb(1.0, Math.floorDiv(level - 1, 2))
  /** The sort's port counts built (`sortPorts`), fewest first. */
  val sortPortChoices: Seq[Int] = Seq(1, 2, 4, 8, 16)
  val default: BroadPhaseParams = BroadPhaseParams()
  /** Four buckets and one-sphere chunks: every cell collides with others in the hash and
    * every cell is visited once per sphere, to test that nothing breaks. */
  val tinyTable: BroadPhaseParams = default.copy(bucketsLog2 = 2, chunk = 1, wordLog2 = 0)
  /** Coarse chunks of up to 32 spheres (the grid's next step), 8 counters a word. */
  val coarse: BroadPhaseParams = default.copy(coarseChunks = true, chunk = 32)
  /** No large list: one huge sphere makes the cell huge (the all-pairs worst case). */
  val noLarge: BroadPhaseParams = default.copy(largeMax = 0)
  /** Four candidate generators. */
  val fourLanes: BroadPhaseParams = default.copy(lanes = 4)
  /** Four candidate generators, the sort's passes two spheres a cycle, 16 counters a word. */
  val fourLanesTwoPorts: BroadPhaseParams = fourLanes.copy(sortPorts = 2, wordLog2 = 4)
  /** Four candidate generators, the sort's passes four spheres a cycle (two sorts of two ports). */
  val fourLanesFourPorts: BroadPhaseParams = fourLanes.copy(sortPorts = 4, wordLog2 = 4)
  /** Eight candidate generators, the sort's passes eight spheres a cycle (four sorts of two ports). */
  val eightLanesEightPorts: BroadPhaseParams = default.copy(lanes = 8, sortPorts = 8, wordLog2 = 4)
}
