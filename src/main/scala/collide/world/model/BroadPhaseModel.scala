package collide.world.model

import collide.fp.model.{Decoded, SoftFloat}
import collide.scpu.ScpuConfig
import collide.scpu.model.{ScpuModel, ScpuPair}
import collide.world.BroadPhaseParams

/** One sphere of a world as the link carries it: link-format bit patterns. */
final case class WorldSphere(x: BigInt, y: BigInt, z: BigInt, r: BigInt) {
  def fields: Seq[BigInt] = Seq(x, y, z, r)
}

/** What the broad phase made of one sphere. */
sealed trait SphereClass
object SphereClass {
  /** A field is NaN or infinite on the link or once converted to the compute format (a
    * binary32 SCPU reading binary64 1e39): never paired, and reported (docs/afu.md). */
  case object Excluded extends SphereClass
  /** Too big for the cell (or not placeable in it): paired with every other sphere. */
  case object Large extends SphereClass
  /** In the grid, at integer cell (cx, cy, cz) = floor(coordinate / edge). */
  final case class Small(cx: Long, cy: Long, cz: Long) extends SphereClass
}

/** Work counts of the reference traversal: what a cycle model of the hardware needs. */
final case class BroadPhaseStats(
    spheres: Int, excluded: Int, large: Int, level: Int, buckets: Int,
    cells: Int,         // chunks' cells: occupied cells, or coarse cells taken as one chunk
    lookups: Long,      // bucket reads: 14 per cell chunk (its cell and 13 half-shell neighbours), 43 per coarse chunk (35 with scanPairs)
    scanned: Long,      // bucket entries streamed past a chunk while visiting those cells
    gridPairs: Long,    // pairs of neighbouring small spheres (before the box filter)
    gridCandidates: Long, largeCandidates: Long, // after the box filter: what the SCPUs get
    cellWork: IndexedSeq[Long], // cycles of one lane on each chunk's cell (or coarse cell), in bucket order
    coarse: Int = 0,    // of the cells, coarse cells taken as one chunk (coarseChunks)
    box: Option[BoxMap] = None, // box buckets' map (boxBuckets)
    walkBuckets: Int = 0 // buckets the prefix sum and the walk cover (walkBuckets)
) {
  def candidates: Long = gridCandidates + largeCandidates
}

final case class BroadPhaseResult(level: Int, classes: IndexedSeq[SphereClass],
                                  candidates: IndexedSeq[(Int, Int)], stats: BroadPhaseStats)

/** A cycle estimate for the planned hardware: counting sort at `sortRate` spheres a cycle,
  * a prefix sum over the buckets a counter word (2^wordLog2) a cycle, occupied cells dealt round-robin to `lanes`
  * candidate generators (each with its own copy of the sorted table), the large list
  * streamed past the table, and the SCPUs taking `scpus` candidates a cycle. A model to size
  * the design, not a measurement of RTL that does not exist yet. */
final case class BroadPhaseCycles(count: Long, prefix: Long, scatter: Long, generate: Long, large: Long,
                                  narrow: Long) {
  /** Passes run one after the other; candidate generation and the SCPUs overlap. */
  def total: Long = count + prefix + scatter + math.max(generate + large, narrow)
}

/** Golden model of the world-mode broad phase (docs/afu.md, "World mode: the broad phase").
  *
  * Why it never misses a pair the SCPU calls a hit: it works on the SCPU's own converted
  * inputs; every small sphere satisfies E >= 2r * m (m = 9/8) for the cell edge E (2^k, or
  * 1.5 * 2^k with two cell steps an octave), and the SCPU's hit decision is exact but for a
  * band of 4 ulps u (docs/scpu.md) and an absolute error below 2^errorExp from underflowing
  * squares, which the cell exceeds 32 times; so a hit between two small spheres has
  * |dx| <= (1 + 4u) E / m + E / 32 <= E (for u <= 2^-7, bf16) on every axis, and their
  * cells, floor(x / E) computed exactly, differ by at most one. Large spheres are paired with everything. A box filter in exact
  * fixed point (boxKey) then drops pairs farther apart than m (ra + rb) on some axis,
  * which no hit is. Why each pair comes out once: a same-cell pair is emitted from its
  * lower index; a neighbour pair from the cell whose offset to the other is in the half
  * shell (exactly one of o, -o is), and a bucket entry is used only if its stored cell is
  * the visited cell, so hash collisions cost time, never a duplicate.
  */
class BroadPhaseModel(val cfg: ScpuConfig, val bp: BroadPhaseParams = BroadPhaseParams.default) {
  import BroadPhaseModel._

  private val scpu = ScpuModel(cfg)
  private val p = cfg.params
  private val lp = cfg.linkParams

  /** The SCPU's view of a sphere: its fields converted to the compute format. */
  def converted(s: WorldSphere): Seq[BigInt] = s.fields.map(scpu.convertIn(_).bits)

  def excluded(s: WorldSphere): Boolean = excluded(s, converted(s))
  /** The same, given the sphere's converted fields (so run() converts each sphere once). */
  def excluded(s: WorldSphere, conv: Seq[BigInt]): Boolean =
    s.fields.exists(b => !isFinite(SoftFloat.decode(lp, b))) || conv.exists(b => !isFinite(SoftFloat.decode(p, b)))

  /** The cell level a converted, finite radius needs: the smallest L whose edge (2^(L/2) for
    * even L, 1.5 * 2^((L-1)/2) for odd L, odd ones only with two cell steps) is >= 2r * margin;
    * Int.MinValue for r <= 0 (fits any cell). */
  def need(rBits: BigInt): Int = SoftFloat.decode(p, rBits) match {
    case Decoded.Finite(false, sig, e) =>
      // 2^k >= 2 r m, and 1.5 * 2^k >= 2 r m (2^k >= 4 r m / 3)
      val even = 2 * (e + ceilLog2(2 * bp.marginNum * sig, bp.marginDen))
      val odd = 2 * (e + ceilLog2(4 * bp.marginNum * sig, 3 * bp.marginDen)) + 1
      if (bp.cellSteps == 2) math.min(even, odd) else even
    case Decoded.Finite(true, _, _) | Decoded.Zero(_) => Int.MinValue
    case d => throw new IllegalArgumentException(s"need: radius $d is not finite (an excluded sphere)")
  }

  /** floor(v / 2^k), exactly; None for a non-finite v. */
  def floorPow2(bits: BigInt, k: Int): Option[Long] = SoftFloat.decode(p, bits) match {
    case Decoded.Zero(_) => Some(0L)
    case Decoded.Finite(neg, sig, e) =>
      val sh = e - k
      val (mag, exact) = if (sh >= 0) (sig << sh, true) else (sig >> -sh, (sig & ((BigInt(1) << -sh) - 1)) == 0)
      val f = if (!neg) mag else if (exact) -mag else -(mag + 1)
      Some(f.toLong)
    case _ => None
  }

  /** The cell coordinate floor(v / edge(level)), exactly: a shift for an edge of 2^k; for
    * 1.5 * 2^k = 3 * 2^(k-1), floor(floor(v / 2^(k-1)) / 3) (floors of floors are floors).
    * None for a non-finite v. */
  def cell(bits: BigInt, level: Int): Option[Long] =
    if ((level & 1) == 0) floorPow2(bits, level / 2)
    else floorPow2(bits, (level - 1) / 2 - 1).map(v => Math.floorDiv(v, 3L))

  /** T with |v| < 2^T; Int.MinValue for zero (no constraint), None if not finite. */
  def topExp(bits: BigInt): Option[Int] = SoftFloat.decode(p, bits) match {
    case Decoded.Zero(_)             => Some(Int.MinValue)
    case Decoded.Finite(_, sig, e)   => Some(e + sig.bitLength)
    case _                           => None
  }

  /** The cell level: as small as the large list, the cell-coordinate width and the
    * subnormal floor allow. At most largeMax spheres then need a bigger cell. */
  def chooseLevel(spheres: IndexedSeq[Seq[BigInt]]): Int = {
    val needs = spheres.map(c => need(c(3))).sorted(Ordering[Int].reverse)
    // Fewer spheres than the large list holds: all in the grid, sized for the biggest.
    val small = if (needs.length > bp.largeMax) needs(bp.largeMax) else needs.headOption.getOrElse(Int.MinValue)
    val tops = spheres.flatMap(_.take(3).flatMap(topExp))
    val coord = if (tops.isEmpty) Int.MinValue else 2 * tops.max.toLong - bp.levelCoordOffset
    math.max(math.max(small.toLong, coord), bp.levelFloor(p).toLong).toInt
  }

  def classify(c: Seq[BigInt], level: Int): SphereClass = {
    if (need(c(3)) > level) SphereClass.Large
    else {
      val Seq(cx, cy, cz) = c.take(3).map(v => cell(v, level).get)
      require(Seq(cx, cy, cz).forall(v => math.abs(v) <= bp.cellLimit), s"cell ($cx,$cy,$cz) outside the guard at level $level")
      SphereClass.Small(cx, cy, cz)
    }
  }

  /** A cell's bucket: the hash of the cell; with coarse chunks, the hash of its coarse cell
    * (2 x 2 x 2 cells) times 8 plus the cell's place in it, so that a coarse cell's 8 cells
    * are 8 consecutive buckets (a group), one contiguous run of the sorted table. */
  def bucket(cx: Long, cy: Long, cz: Long, box: Option[BoxMap] = None): Int = {
    def hash(x: Long, y: Long, z: Long) = box match {
      case None => (x * HashX) ^ (y * HashY) ^ (z * HashZ)
      case Some(b) => b.index(x, y, z)
    }
    val h =
      if (!bp.coarseChunks) hash(cx, cy, cz)
      else (hash(cx >> 1, cy >> 1, cz >> 1) << 3) | ((cx & 1) << 2) | ((cy & 1) << 1) | (cz & 1)
    (h & (bp.buckets - 1).toLong).toInt
  }

  /** With `boxBuckets`, the map of the world's box (docs/afu.md, "Box buckets"): per axis, the
    * units of the hash (cells, or coarse cells with coarse chunks) of the least and the
    * greatest coordinate of any eligible sphere at `level`. A unit's bucket (its group of 8
    * with coarse chunks) is its place in the box, numbered x first with one unit of padding
    * per axis (BoxMap.index), modulo the buckets in use: where the padded box fits
    * (BoxMap.fits), no two units of the world share a bucket and no neighbour outside the box
    * falls in an occupied one. None without boxBuckets or without an eligible sphere
    * (Teschner's hash). */
  def boxMap(conv: IndexedSeq[Seq[BigInt]], level: Int): Option[BoxMap] =
    if (!bp.boxBuckets || conv.isEmpty) None
    else {
      val unitShift = if (bp.coarseChunks) 1 else 0
      // Float order of finite bit patterns as unsigned keys: negatives' bits inverted, the
      // sign bit set on the rest (what the hardware compares).
      val sign = BigInt(1) << (p.width - 1)
      def key(b: BigInt): BigInt = if (b.testBit(p.width - 1)) (~b) & (sign * 2 - 1) else b | sign
      val ends = (0 until 3).map { a =>
        val vs = conv.map(_(a))
        def unit(v: BigInt): Long = cell(v, level).get >> unitShift
        (unit(vs.minBy(key)), unit(vs.maxBy(key)))
      }
      Some(BoxMap(ends.map(_._1), ends.map(e => e._2 - e._1 + 1)))
    }

  /** The buckets the prefix sum and the walk cover, of `nb` in use: where the box's places fit
    * them, the buckets of its places (a group of 8 each with coarse chunks) rounded up to a
    * word of `perWord` counters; else all `nb`. No unit of the world or neighbour of one is in
    * a bucket past them. */
  def walkBuckets(nb: Int, box: Option[BoxMap], perWord: Int): Int = {
    val groupLog2 = if (bp.coarseChunks) 3 else 0
    val hashBits = math.max(0, Integer.numberOfTrailingZeros(nb) - groupLog2)
    box match {
      case Some(b) if b.fits(hashBits) =>
        val buckets = (b.places << groupLog2).toLong
        math.min(nb.toLong, (buckets + perWord - 1) / perWord * perWord).toInt
      case _ => nb
    }
  }

  /** Buckets used for n spheres: at least n 2^bucketsPerSphereLog2 (2n by default: load factor
    * <= 1/2), at most the table. */
  def bucketsFor(n: Int): Int = {
    var b = 1
    while (b < (n.toLong << bp.bucketsPerSphereLog2) && b < bp.buckets) b <<= 1
    b
  }

  /** The box filter's fixed-point view of a sphere at cell level L, k = ceil(L / 2) (the
    * octave the edge lies in): floor(v * 2^(F-k)) for the coordinates and
    * ceil(r * margin * 2^(F-k)) for the radius, all exact. A pair
    * passes iff |qa - qb| <= qr_a + qr_b + boxSlack(k) on every axis: every SCPU hit has
    * |va - vb| <= margin (ra + rb) + 2^errorExp, and floors of two reals less than an
    * integer T + 1 apart differ by at most T, so no hit is filtered out. */
  def boxKey(c: Seq[BigInt], level: Int): (BigInt, BigInt, BigInt, BigInt) = {
    val sh = bp.filterFracBits - BroadPhaseParams.filterExp(level)
    def scaled(bits: BigInt): (BigInt, BigInt, Boolean) = SoftFloat.decode(p, bits) match { // (mag num, den, negative)
      case Decoded.Finite(neg, sig, e) =>
        val t = e + sh
        if (t >= 0) (sig << t, BigInt(1), neg) else (sig, BigInt(1) << -t, neg)
      case _ => (BigInt(0), BigInt(1), false)
    }
    def floorQ(bits: BigInt) = { val (n, d, neg) = scaled(bits); if (!neg) n / d else -((n + d - 1) / d) }
    val (rn, rd, rneg) = scaled(c(3))
    val qr = if (rneg) BigInt(0) else (rn * bp.marginNum + rd * bp.marginDen - 1) / (rd * bp.marginDen)
    (floorQ(c(0)), floorQ(c(1)), floorQ(c(2)), qr)
  }

  val errorExp: Int = bp.errorExp(p)

  /** The box filter's slack in fixed-point units at cell level L: 1 for the floors, plus
    * the absolute error 2^errorExp rounded up to whole units. */
  def boxSlack(level: Int): BigInt = {
    val e = errorExp + bp.filterFracBits - BroadPhaseParams.filterExp(level)
    1 + (if (e >= 0) BigInt(1) << e else BigInt(1))
  }

  def boxPass(a: (BigInt, BigInt, BigInt, BigInt), b: (BigInt, BigInt, BigInt, BigInt), slack: BigInt): Boolean = {
    val t = a._4 + b._4 + slack
    (a._1 - b._1).abs <= t && (a._2 - b._2).abs <= t && (a._3 - b._3).abs <= t
  }

  /** The reference traversal. Counting sort of the small spheres into buckets by cell; then
    * cell by cell (in bucket order), the cell's spheres, in chunks of `chunk`, are held
    * while its own cell and its 13 half-shell neighbours stream past; neighbour pairs that
    * pass the box filter are candidates. Then each large sphere meets every other sphere. */
  def run(world: IndexedSeq[WorldSphere]): BroadPhaseResult = {
    val n = world.length
    val conv = world.map(converted)
    val isExcluded = world.indices.map(i => excluded(world(i), conv(i)))
    val eligible = world.indices.filterNot(isExcluded)
    val level = chooseLevel(eligible.map(conv))
    val classes: IndexedSeq[SphereClass] = world.indices.map(i => if (isExcluded(i)) SphereClass.Excluded else classify(conv(i), level))
    val box = world.indices.map(i => if (isExcluded(i)) null else boxKey(conv(i), level))
    val slack = boxSlack(level)
    val smalls = world.indices.flatMap(i => classes(i) match { case s: SphereClass.Small => Some(i -> s); case _ => None })
    val nb = bucketsFor(n) // the hardware knows n before it knows which spheres are small
    val boxed = boxMap(eligible.map(conv), level)
    val walk = walkBuckets(nb, boxed, 1 << math.min(bp.wordLog2, bp.bucketsLog2))
    def bucketOf(c: SphereClass.Small) = bucket(c.cx, c.cy, c.cz, boxed) & (nb - 1)

    val (start, entries) = countingSort(smalls.map { case (i, c) => i -> bucketOf(c) }, nb)
    assert(start(walk) == smalls.length, s"a sphere's bucket is past the $walk buckets the walk covers")
    def cellOf(i: Int) = classes(i).asInstanceOf[SphereClass.Small]

    val out = IndexedSeq.newBuilder[(Int, Int)]
    var lookups, scanned, gridPairs, grid = 0L
    val work = IndexedSeq.newBuilder[Long]
    var cells, coarseCount = 0
    // Neighbouring small spheres i and j: a candidate if the box filter passes.
    def meet(i: Int, j: Int): Unit = {
      gridPairs += 1
      if (boxPass(box(i), box(j), slack)) { out += ((math.min(i, j), math.max(i, j))); grid += 1 }
    }
    // The visits of one chunk: each visited cell's bucket streams past it; a member takes an
    // entry of the visited cell if it owns the pair. Returns the cycles of the stream.
    def visit(chunk: IndexedSeq[Int], visited: Seq[SphereClass.Small]): Long = {
      var w = 0L
      for (nc <- visited) {
        val ob = bucketOf(nc)
        val len = start(ob + 1) - start(ob)
        lookups += 1; scanned += len; w += math.max(1, len)
        for (e <- start(ob) until start(ob + 1); j = entries(e) if cellOf(j) == nc; i <- chunk if owns(cellOf(i), nc, i, j))
          meet(i, j)
      }
      w
    }
    def around(base: SphereClass.Small, offsets: Seq[(Int, Int, Int)]) =
      offsets.map(o => SphereClass.Small(base.cx + o._1, base.cy + o._2, base.cz + o._3))
    // The walk goes over groups of 8 buckets (with coarse chunks a coarse cell's cells; a
    // smaller table is one group). A group whose spheres fit a chunk is taken coarse cell by
    // coarse cell in order of first entry, each one chunk with its 43 visits; any other group
    // (and every group without coarse chunks) bucket by bucket, cell by cell in order of
    // first entry, in chunks of `chunk` with their own cell and 13 half-shell neighbours.
    for (g <- 0 until walk by 8) {
      val (lo, hi) = (g, math.min(nb, g + 8))
      val run = (start(lo) until start(hi)).map(entries) // the group's entries in table order
      if (bp.coarseChunks && run.nonEmpty && run.length <= bp.chunk) {
        def coarseOf(i: Int) = { val c = cellOf(i); SphereClass.Small(c.cx >> 1 << 1, c.cy >> 1 << 1, c.cz >> 1 << 1) }
        val leaders = run.map(coarseOf).distinct
        for (base <- leaders) {
          val chunk = run.filter(coarseOf(_) == base)
          cells += 1; coarseCount += 1
          // The scan runs from its leader to the group's end.
          val scan = run.length - run.indexWhere(coarseOf(_) == base)
          // With scanPairs each member meets those loaded before it as the scan loads it, and
          // the chunk's own 8 cells are not visited.
          if (bp.scanPairs) for ((j, k) <- chunk.zipWithIndex; i <- chunk.take(k)) meet(i, j)
          work += scan + visit(chunk, around(base, if (bp.scanPairs) CoarseOthers else CoarseVisits))
        }
      } else for (b <- lo until hi) {
        val members = (start(b) until start(b + 1)).map(entries)
        for ((cell, own) <- members.groupBy(cellOf).toSeq.sortBy(_._2.head)) {
          cells += 1
          work += own.grouped(bp.chunk).map(c => c.length + visit(c, around(cell, Visits))).sum
        }
      }
    }
    val larges = world.indices.filter(classes(_) == SphereClass.Large)
    var largePairs = 0L
    for (l <- larges; j <- eligible if j != l && (classes(j) != SphereClass.Large || j > l) && boxPass(box(l), box(j), slack)) {
      out += ((math.min(l, j), math.max(l, j))); largePairs += 1
    }
    val stats = BroadPhaseStats(n, n - eligible.length, larges.length, level, nb, cells, lookups, scanned, gridPairs, grid,
      largePairs, work.result(), coarseCount, boxed, walk)
    BroadPhaseResult(level, classes, out.result(), stats)
  }

  /** The candidate set by its definition, all pairs checked (tests compare run() with it). */
  def candidatesByDefinition(r: BroadPhaseResult, world: IndexedSeq[WorldSphere]): Set[(Int, Int)] = {
    def near(a: SphereClass, b: SphereClass): Boolean = (a, b) match {
      case (SphereClass.Excluded, _) | (_, SphereClass.Excluded) => false
      case (SphereClass.Large, _) | (_, SphereClass.Large)       => true
      case (a: SphereClass.Small, b: SphereClass.Small) =>
        math.abs(a.cx - b.cx) <= 1 && math.abs(a.cy - b.cy) <= 1 && math.abs(a.cz - b.cz) <= 1
    }
    val n = r.classes.length
    val box = world.map(s => boxKey(converted(s), r.level))
    val slack = boxSlack(r.level)
    (for (i <- 0 until n; j <- i + 1 until n if near(r.classes(i), r.classes(j)) && boxPass(box(i), box(j), slack)) yield (i, j)).toSet
  }

  /** The SCPU's hit decision for spheres i and j (what the broad phase must not miss). */
  def scpuHit(world: IndexedSeq[WorldSphere], i: Int, j: Int): Boolean = {
    val a = world(i); val b = world(j)
    scpu.collide(ScpuPair(a.x, a.y, a.z, a.r, b.x, b.y, b.z, b.r, 0)).hit
  }

  def cycles(r: BroadPhaseResult, lanes: Int, scpus: Int, sortRate: Int = 1): BroadPhaseCycles = {
    require(lanes >= 1 && scpus >= 1 && sortRate >= 1)
    val st = r.stats
    val small = (st.spheres - st.excluded - st.large).toLong
    val perLane = Array.fill(lanes)(0L)
    st.cellWork.zipWithIndex.foreach { case (w, c) => perLane(c % lanes) += w }
    val eligible = (st.spheres - st.excluded).toLong
    def div(a: Long, b: Long) = (a + b - 1) / b
    BroadPhaseCycles(
      count = div(st.spheres, sortRate),
      prefix = div(st.walkBuckets, 1L << bp.wordLog2),
      scatter = div(small, sortRate),
      generate = perLane.max,
      large = div(st.large * eligible, lanes),
      narrow = div(st.candidates, scpus))
  }
}

/** Box buckets' map (BroadPhaseModel.boxMap): the box's least unit on each axis and its
  * extent in units. A unit's place is its offset from the origin one unit below the box,
  * numbered x first, then y, then z, with radices one more than the extents: place 0 of each
  * row, row 0 of each layer and the layers below and above the box are padding, where every
  * neighbour just outside the box lands, so no neighbour meets a sphere of another unit and
  * every place is at least 0 and below `places`. */
final case class BoxMap(lo: Seq[Long], extent: Seq[Long]) {
  require(lo.length == 3 && extent.length == 3 && extent.forall(_ >= 1), s"box $lo $extent")
  val origin: Seq[Long] = lo.map(_ - 1)
  val radix: Seq[Long] = extent.map(_ + 1)
  def index(x: Long, y: Long, z: Long): Long = (x - origin(0)) + radix(0) * ((y - origin(1)) + radix(1) * (z - origin(2)))
  /** One more than the greatest place of a unit in the box or next to it. */
  def places: BigInt = BigInt(radix(0)) * radix(1) * (extent(2) + 2) + radix(0) + 1
  /** The places fit 2^hashBits: no two units share a bucket, and no bucket past them is used. */
  def fits(hashBits: Int): Boolean = places <= (BigInt(1) << hashBits)
  /** The extents as the status reports them: saturated at `w` bits. */
  def reported(w: Int): Seq[Long] = extent.map(e => math.min(e, (1L << w) - 1))
}

object BroadPhaseModel {
  // Teschner et al.'s spatial-hash primes; only their low bits matter to the bucket index.
  val HashX = 73856093L
  val HashY = 19349663L
  val HashZ = 83492791L

  val Own: (Int, Int, Int) = (0, 0, 0)
  /** The 13 neighbour offsets o with o > 0 in lexicographic order: of o and -o exactly one. */
  val HalfShell: Seq[(Int, Int, Int)] = for {
    dx <- -1 to 1; dy <- -1 to 1; dz <- -1 to 1
    if dx > 0 || (dx == 0 && dy > 0) || (dx == 0 && dy == 0 && dz > 0)
  } yield (dx, dy, dz)
  val Visits: Seq[(Int, Int, Int)] = Own +: HalfShell

  /** A coarse cell's 8 cells, as offsets from twice its coordinates. */
  val CoarseBlock: Seq[(Int, Int, Int)] = for (x <- 0 to 1; y <- 0 to 1; z <- 0 to 1) yield (x, y, z)
  /** The cells a coarse chunk streams: every cell in the own or half-shell neighbourhood of one
    * of its 8, as offsets from twice its coordinates, in order of first appearance (Visits by
    * block cell): 43 of them. */
  val CoarseVisits: Seq[(Int, Int, Int)] =
    (for (o <- Visits; b <- CoarseBlock) yield (b._1 + o._1, b._2 + o._2, b._3 + o._3)).distinct
  /** CoarseVisits without the coarse cell's own 8 (its first 8): the cells a coarse chunk
    * streams with scanPairs, whose scan pairs its members among themselves: 35. */
  val CoarseOthers: Seq[(Int, Int, Int)] = CoarseVisits.drop(CoarseBlock.length)
  require(CoarseVisits.take(CoarseBlock.length) == CoarseBlock)
  /** Whether a member i in cell `mine` takes sphere j of cell `visited`: the half-shell rule of
    * Visits, per member (j's cell its own with j > i, or in its half shell). */
  def owns(mine: SphereClass.Small, visited: SphereClass.Small, i: Int, j: Int): Boolean = {
    val o = ((visited.cx - mine.cx).toInt, (visited.cy - mine.cy).toInt, (visited.cz - mine.cz).toInt)
    if (o == Own) j > i else HalfShellSet(o)
  }
  private val HalfShellSet: Set[(Int, Int, Int)] = HalfShell.toSet

  private def isFinite(d: Decoded): Boolean = d match {
    case Decoded.Zero(_) | Decoded.Finite(_, _, _) => true
    case _                                         => false
  }

  /** Counting sort of (item, bucket) pairs into `buckets` buckets: count, exclusive prefix
    * sum, scatter in input order (stable). Returns start (buckets + 1 entries: bucket b is
    * entries(start(b) until start(b + 1))) and the sorted items. BucketSort's golden model. */
  def countingSort(items: Seq[(Int, Int)], buckets: Int): (Array[Int], Array[Int]) = {
    val count = new Array[Int](buckets)
    items.foreach { case (_, b) => count(b) += 1 }
    val start = count.scanLeft(0)(_ + _)
    val fill = start.clone()
    val entries = new Array[Int](items.length)
    items.foreach { case (i, b) => entries(fill(b)) = i; fill(b) += 1 }
    (start, entries)
  }

  /** The smallest integer t with 2^t * b >= a (a, b > 0). */
  def ceilLog2(a: BigInt, b: BigInt): Int = {
    require(a > 0 && b > 0)
    def atLeast(t: Int) = if (t >= 0) (b << t) >= a else b >= (a << -t)
    var t = a.bitLength - b.bitLength
    while (!atLeast(t)) t += 1
    while (atLeast(t - 1)) t -= 1
    t
  }
}
