package collide.world

import java.math.{BigDecimal => JBigDecimal, RoundingMode => JRoundingMode}
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.FloatFormat
import collide.scpu.ScpuConfig
import collide.scpu.model.ScpuModel
import collide.testutil.Seeds
import collide.world.BroadPhaseWorlds._
import collide.world.model._

class BroadPhaseModelSpec extends AnyFlatSpec {
  behavior of "BroadPhaseModel"

  private val presets = Seq(ScpuConfig.fp32, ScpuConfig.fp32RsqrtDr, ScpuConfig.fp32Nr, ScpuConfig.fp32Robust,
    ScpuConfig.fp64, ScpuConfig.fp24, ScpuConfig.fp16, ScpuConfig.bf16)

  /** The hard cases and random clouds, small enough to check every pair with the SCPU model. */
  private def worlds(name: String): Seq[(String, Seq[S])] =
    hardCases(Seeds.rng(s"BroadPhaseModelSpec-$name"), onePointSpheres = 24)

  private def checkWorld(model: BroadPhaseModel, label: String, w: IndexedSeq[WorldSphere]): BroadPhaseResult = {
    val r = model.run(w)
    val c = r.candidates
    assert(c.distinct.length == c.length, s"$label: a pair came out twice")
    assert(c.forall { case (i, j) => i < j }, s"$label: a pair with i >= j")
    val set = c.toSet
    assert(set == model.candidatesByDefinition(r, w), s"$label: the traversal differs from the candidate set's definition")
    val eligible = w.indices.filter(r.classes(_) != SphereClass.Excluded)
    for (a <- eligible.indices; b <- a + 1 until eligible.length) {
      val (i, j) = (eligible(a), eligible(b))
      if (model.scpuHit(w, i, j))
        assert(set((i, j)), s"$label (${model.cfg.name}, level ${r.level}): the SCPU calls ($i,$j) a hit but the broad phase " +
          s"missed it: ${w(i)} ${w(j)} classes ${r.classes(i)} ${r.classes(j)}")
    }
    assert(r.stats.large <= model.bp.largeMax, s"$label: ${r.stats.large} large spheres > largeMax")
    r
  }

  for (cfg <- presets) {
    it should s"find every pair the ${cfg.name} SCPU calls a hit, each once, in every hard case and random cloud" in {
      val model = new BroadPhaseModel(cfg)
      for ((label, w) <- worlds(cfg.name)) checkWorld(model, label, bits(cfg.linkFormat, w))
    }
  }

  for (cfg <- presets) {
    it should s"find every pair the ${cfg.name} SCPU calls a hit with cells of edge 2^k and 1.5 * 2^k (two steps an octave)" in {
      val model = new BroadPhaseModel(cfg, BroadPhaseParams.default.copy(cellSteps = 2))
      for ((label, w) <- worlds(cfg.name)) checkWorld(model, label, bits(cfg.linkFormat, w))
    }
  }

  for ((bp, what) <- Seq(BroadPhaseParams.default.copy(coarseChunks = true) -> "chunks of 16",
                         BroadPhaseParams.default.copy(coarseChunks = true, cellSteps = 2, chunk = 32) -> "cells of 1.5 * 2^k too, chunks of 32",
                         BroadPhaseParams.tinyTable.copy(coarseChunks = true, wordLog2 = 3) -> "a four-bucket table, one-sphere chunks",
                         BroadPhaseParams.default.copy(coarseChunks = true, cellSteps = 2, chunk = 32, scanPairs = true) ->
                           "chunks of 32 whose members pair as the scan loads them",
                         BroadPhaseParams.default.copy(coarseChunks = true, cellSteps = 2, chunk = 32, scanPairs = true, boxBuckets = true) ->
                           "pairs in the scan, box buckets",
                         BroadPhaseParams.tinyTable.copy(coarseChunks = true, wordLog2 = 3, scanPairs = true) -> "a four-bucket table, pairs in the scan");
       cfg <- Seq(ScpuConfig.fp32, ScpuConfig.bf16, ScpuConfig.fp64)) {
    it should s"find exactly today's candidates with coarse chunks ($what), every ${cfg.name} hit once, in every hard case and random cloud" in {
      val model = new BroadPhaseModel(cfg, bp)
      val today = new BroadPhaseModel(cfg, bp.copy(coarseChunks = false, scanPairs = false))
      for ((label, w) <- worlds(s"coarse-${cfg.name}")) {
        val world = bits(cfg.linkFormat, w)
        val r = checkWorld(model, s"$label, coarse chunks", world)
        val t = today.run(world)
        assert(r.candidates.toSet == t.candidates.toSet, s"$label: coarse chunks give other candidates than today's")
        assert(r.stats.gridCandidates == t.stats.gridCandidates && r.stats.cells <= t.stats.cells, s"$label: ${r.stats} against ${t.stats}")
      }
    }
  }

  it should "stream fewer spheres past its chunks with coarse chunks on a sparse cloud, and keep today's chunks where a coarse cell overfills one" in {
    val rng = Seeds.rng("BroadPhaseModelSpec-coarse-work")
    // Four buckets a sphere: a group whose coarse cell shares it with another by hash collision
    // is taken cell by cell (the group's total decides), and with two a sphere those
    // collisions alone move the share from about 0.47 to 0.56-0.63 (40 seeds), across the bound.
    val bp = BroadPhaseParams.default.copy(cellSteps = 2, chunk = 32, bucketsPerSphereLog2 = 2)
    val (coarse, today) = (new BroadPhaseModel(ScpuConfig.fp32, bp.copy(coarseChunks = true)), new BroadPhaseModel(ScpuConfig.fp32, bp))
    val sparse = bits(FloatFormat.fp32, uniform(rng, 2000))
    val (cr, tr) = (coarse.run(sparse), today.run(sparse))
    val (c, t) = (cr.stats, tr.stats)
    println(s"[BroadPhaseModelSpec] uniform 2000: scanned ${t.scanned} -> ${c.scanned}, lookups ${t.lookups} -> ${c.lookups}, " +
      s"generate (16 lanes) ${today.cycles(tr, 16, 16).generate} -> ${coarse.cycles(cr, 16, 16).generate}")
    assert(c.scanned < t.scanned * 6 / 10, s"coarse chunks should stream under 60 % of today's spheres: ${c.scanned} against ${t.scanned}")
    // 40 equal spheres at one point: a coarse cell of 40 > 32, so today's chunks, the same work.
    val dense = bits(FloatFormat.fp32, Seq.fill(40)(S(1.5, -2.25, 3.0, 0.5)))
    val (cd, td) = (coarse.run(dense).stats, today.run(dense).stats)
    assert(cd.scanned == td.scanned && cd.lookups == td.lookups && cd.cellWork == td.cellWork, s"$cd against $td")
  }

  it should "visit 8 cells fewer a coarse chunk with pairs in the scan, streaming each member once where the box fits, for the same candidates" in {
    val rng = Seeds.rng("BroadPhaseModelSpec-scan-pairs")
    val bp = BroadPhaseParams.default.copy(coarseChunks = true, cellSteps = 2, chunk = 32, boxBuckets = true)
    val (paired, visited) = (new BroadPhaseModel(ScpuConfig.fp32, bp.copy(scanPairs = true)), new BroadPhaseModel(ScpuConfig.fp32, bp))
    for ((label, w) <- Seq("uniform" -> uniform(rng, 2000), "clustered" -> clustered(rng, 2000, clusters = 8))) {
      val world = bits(FloatFormat.fp32, w)
      val (p, v) = (paired.run(world), visited.run(world))
      println(s"[BroadPhaseModelSpec] $label 2000: lookups ${v.stats.lookups} -> ${p.stats.lookups}, streamed ${v.stats.scanned} -> ${p.stats.scanned}, " +
        s"generate (16 lanes) ${visited.cycles(v, 16, 16).generate} -> ${paired.cycles(p, 16, 16).generate}")
      assert(p.candidates.toSet == v.candidates.toSet && p.candidates.length == v.candidates.length, s"$label: other candidates")
      assert(p.stats.coarse > 0 && p.stats.coarse == v.stats.coarse, s"$label: ${p.stats}")
      assert(v.stats.lookups - p.stats.lookups == 8L * p.stats.coarse, s"$label: lookups ${v.stats.lookups} -> ${p.stats.lookups}")
      // Where the padded box fits, a coarse chunk's own 8 buckets hold its members alone: the
      // entries no longer visited are exactly the spheres in coarse chunks.
      if (v.stats.box.exists(_.fits(Integer.numberOfTrailingZeros(v.stats.buckets) - 3))) {
        val inCoarse = v.stats.scanned - p.stats.scanned
        assert(inCoarse > 0 && inCoarse <= world.length, s"$label: ${v.stats.scanned} -> ${p.stats.scanned} entries streamed")
      }
    }
  }

  for ((bp, what) <- Seq(BroadPhaseParams.default.copy(coarseChunks = true, cellSteps = 2, chunk = 32) -> "coarse chunks of 32, cells of 1.5 * 2^k too",
                         BroadPhaseParams.default -> "cells of 2^k, no coarse chunks",
                         BroadPhaseParams.tinyTable.copy(coarseChunks = true, wordLog2 = 3) -> "a four-bucket table, coarse chunks of one");
       cfg <- Seq(ScpuConfig.fp32, ScpuConfig.bf16, ScpuConfig.fp64)) {
    it should s"find exactly the hashed table's candidates with box buckets ($what), every ${cfg.name} hit once, in every hard case and random cloud" in {
      val model = new BroadPhaseModel(cfg, bp.copy(boxBuckets = true))
      val hashed = new BroadPhaseModel(cfg, bp)
      for ((label, w) <- worlds(s"box-${cfg.name}")) {
        val world = bits(cfg.linkFormat, w)
        val r = checkWorld(model, s"$label, box buckets", world)
        assert(r.candidates.toSet == hashed.run(world).candidates.toSet, s"$label: box buckets give other candidates than the hash")
        assert(r.stats.box.isDefined == r.classes.exists(_ != SphereClass.Excluded), s"$label: box ${r.stats.box}")
      }
    }
  }

  /** The distinct hash units (cells, or coarse cells) of a world's small spheres, and the buckets' units they fall in. */
  private def units(model: BroadPhaseModel, r: BroadPhaseResult): (Int, Int) = {
    val shift = if (model.bp.coarseChunks) 1 else 0
    val nb = r.stats.buckets
    val cells = r.classes.collect { case c: SphereClass.Small => c }.distinct
    val us = cells.map(c => (c.cx >> shift, c.cy >> shift, c.cz >> shift)).distinct
    val hashes = cells.map(c => (model.bucket(c.cx, c.cy, c.cz, r.stats.box) & (nb - 1)) >> (3 * shift)).distinct
    (us.length, hashes.length)
  }

  it should "give every coarse cell of a world its own buckets, and every neighbour outside its box an empty one, where the padded box fits the table" in {
    val bp = BroadPhaseParams.default.copy(coarseChunks = true, boxBuckets = true)
    val model = new BroadPhaseModel(ScpuConfig.fp32, bp)
    // Radius 0.5 needs a cell of 2 (2^1 >= 1.125), a coarse cell of 4: x over coarse cells
    // -2..2 (extent 5), y in one (1), z over 0..2 (3). Padded: radices 6 and 2, 6 * 2 * (3 + 2)
    // + 6 + 1 = 67 places.
    def world(n: Int) = bits(FloatFormat.fp32, (0 until n).map(i => S(-8.0 + 4.0 * (i % 5), 1.0, 4.0 * (i / 5 % 3), 0.5)))
    val small = model.run(world(15))
    assert(small.level == 2 && small.stats.buckets == 32 && small.stats.box.contains(BoxMap(Seq(-2, 0, 0), Seq(5, 1, 3))),
      s"${small.level} ${small.stats}")
    assert(small.stats.box.get.places == 67)
    // 64 spheres (128 buckets: 16 groups of 8) cannot hold 67 places: units share groups.
    val wrapped = model.run(world(64))
    assert(!wrapped.stats.box.get.fits(4) && units(model, wrapped)._2 < 15, s"${units(model, wrapped)}")
    // 512 spheres (1024 buckets: 128 groups): it fits, 15 coarse cells in 15 groups, and every
    // coarse cell next to the box (none of the world's) in a group no sphere is in.
    val fits = model.run(world(512))
    val box = fits.stats.box.get
    assert(box.fits(7) && units(model, fits) == (15, 15), s"$box ${units(model, fits)}")
    val nb = fits.stats.buckets
    def group(x: Long, y: Long, z: Long) = (model.bucket(2 * x, 2 * y, 2 * z, Some(box)) & (nb - 1)) >> 3
    val inside = for (x <- -2L to 2; y <- 0L to 0; z <- 0L to 2) yield (x, y, z)
    val occupied = inside.map { case (x, y, z) => group(x, y, z) }.toSet
    val around = for (x <- -3L to 3; y <- -1L to 1; z <- -1L to 3 if !inside.contains((x, y, z))) yield group(x, y, z)
    assert(around.forall(g => !occupied.contains(g)), s"a neighbour outside the box shares a group with the world")
    // Every place, in the box or next to it, is below `places`: the walk covers 67 groups of
    // 8 buckets, rounded up to a word (perWord counters), not the 1,024 buckets in use.
    val all = for (x <- -3L to 3; y <- -1L to 1; z <- -1L to 3) yield box.index(x, y, z)
    assert(all.forall(i => i >= 0 && i < box.places), s"places ${all.min}..${all.max}, want 0 until ${box.places}")
    val perWord = 1 << bp.wordLog2
    assert(fits.stats.walkBuckets == (67 * 8 + perWord - 1) / perWord * perWord && fits.stats.walkBuckets < nb, s"${fits.stats.walkBuckets}")
    assert(wrapped.stats.walkBuckets == wrapped.stats.buckets)
    // The padding is what keeps them apart: numbered without it, x = -3 in layer z = 1 would be
    // the world's x = 2 in layer 0; padded, it is the padding row's last place.
    def tight(x: Long, y: Long, z: Long) = (x - box.lo(0)) + box.extent(0) * ((y - box.lo(1)) + box.extent(1) * (z - box.lo(2)))
    assert(tight(-3, 0, 1) == tight(2, 0, 0) && box.index(-3, 0, 1) == box.index(3, 1, 0))
    // A uniform cloud: every coarse cell its own group where the hash shares some, fewer spheres streamed.
    val rng = Seeds.rng("BroadPhaseModelSpec-box")
    val cloud = bits(FloatFormat.fp32, uniform(rng, 2000))
    val boxed = new BroadPhaseModel(ScpuConfig.fp32, bp.copy(cellSteps = 2, chunk = 32))
    val hashed = new BroadPhaseModel(ScpuConfig.fp32, bp.copy(cellSteps = 2, chunk = 32, boxBuckets = false))
    val (b, h) = (boxed.run(cloud), hashed.run(cloud))
    val (bu, hu) = (units(boxed, b), units(hashed, h))
    println(s"[BroadPhaseModelSpec] uniform 2000: box ${b.stats.box}, coarse cells ${bu._1} in ${bu._2} groups (hash: ${hu._2}), " +
      s"streamed ${h.stats.scanned} -> ${b.stats.scanned}")
    assert(bu._1 == bu._2 && hu._2 < hu._1, s"box $bu, hash $hu")
    assert(b.stats.scanned < h.stats.scanned, s"box buckets streamed ${b.stats.scanned}, the hash ${h.stats.scanned}")
    assert(boxed.run(IndexedSeq.empty).stats.box.isEmpty)
  }

  it should "give the same candidates when every cell collides with others in a four-bucket table" in {
    val model = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.tinyTable)
    for ((label, w) <- worlds("tiny-table")) checkWorld(model, label, bits(FloatFormat.fp32, w))
  }

  it should "stay exact with no large list, one huge sphere making the cell huge" in {
    val model = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.noLarge)
    val r = checkWorld(model, "huge, no large list", bits(FloatFormat.fp32, huge(Seeds.rng("BroadPhaseModelSpec-noLarge"), 60, 1)))
    assert(r.stats.large == 0 && BroadPhaseParams.edge(r.level) >= 32, s"level ${r.level}: the huge sphere should have set the cell")
  }

  it should "choose a larger cell when more spheres are huge than the large list holds" in {
    val rng = Seeds.rng("BroadPhaseModelSpec-overfull")
    val model = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.default.copy(largeMax = 2))
    val r = checkWorld(model, "five huge, largeMax 2", bits(FloatFormat.fp32, huge(rng, 60, 5)))
    assert(r.stats.large == 2, s"${r.stats.large} large: the two biggest should be large, the rest in the grid")
  }

  it should "exclude spheres with a NaN or infinite field and pair the rest" in {
    val f = FloatFormat.fp32
    val nan = BigInt(java.lang.Float.floatToRawIntBits(Float.NaN).toLong & 0xffffffffL)
    val w = bits(f, Seq(S(0, 0, 0, 0.5), S(0.5, 0, 0, 0.5), S(0.2, 0, 0, 0.5)))
    val world = w.updated(2, w(2).copy(y = nan)) :+ w(0).copy(r = f.infinity(false))
    val model = new BroadPhaseModel(ScpuConfig.fp32)
    val r = model.run(world)
    assert(r.classes(2) == SphereClass.Excluded && r.classes(3) == SphereClass.Excluded)
    assert(r.candidates == Seq((0, 1)))
    // Finite on the binary32 link, infinite once rounded to fp24: excluded too.
    val fp24 = new BroadPhaseModel(ScpuConfig.fp24)
    val edge = w :+ w(0).copy(x = f.maxFinite(false))
    assert(fp24.run(edge).classes(3) == SphereClass.Excluded)
  }

  it should "make a cell of edge 2^k at least 2r * 9/8 with one cell step an octave: 2 for radius 0.5, 1 for 0.4375" in {
    val model = new BroadPhaseModel(ScpuConfig.fp32)
    def edge(r: Double) = BroadPhaseParams.edge(model.run(bits(FloatFormat.fp32, Seq(S(0, 0, 0, r), S(3, 0, 0, r)))).level)
    assert(edge(0.5) == 2)      // 1.125 -> 2
    assert(edge(0.4375) == 1)   // 0.984375 -> 1
    assert(edge(4.0 / 9) == 2)  // binary32's 4/9 is 0.44444445 > 4/9: 1.0000000 + -> 2
    assert(edge(0.3) == 1)      // 0.675 -> 1
    assert(edge(0.1) == 0.25)   // the diamond's radius: 0.225 -> 0.25
  }

  it should "make a cell of edge 2^k or 1.5 * 2^k at least 2r * 9/8 with two steps: 1.5 for radius 0.5, 0.75 for 0.3" in {
    val model = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.default.copy(cellSteps = 2))
    def level(r: Double) = model.run(bits(FloatFormat.fp32, Seq(S(0, 0, 0, r), S(3, 0, 0, r)))).level
    assert(level(0.5) == 1 && BroadPhaseParams.edge(1) == 1.5)   // 1.125 -> 1.5
    assert(level(0.4375) == 0)                                    // 0.984375 -> 1
    assert(level(4.0 / 9) == 1)                                   // 1.0000000 + -> 1.5
    assert(level(2.0 / 3) == 2)                                   // binary32's 2/3 is 0.6666667 > 2/3: 1.5000001 -> 2
    assert(level(0.6666666) == 1)                                 // 1.4999999 -> 1.5
    assert(level(0.3) == -1 && BroadPhaseParams.edge(-1) == 0.75) // 0.675 -> 0.75
    assert(level(0.1) == -4)                                      // 0.225 -> 0.25 (0.1875 is too small)
    assert(level(0.08) == -5 && BroadPhaseParams.edge(-5) == 0.1875) // 0.18 -> 0.1875
  }

  it should "compute floor(v / edge) exactly for edges 2^k and 1.5 * 2^k, negatives and subnormals included" in {
    val rng = Seeds.rng("BroadPhaseModelSpec-floor")
    for (cfg <- Seq(ScpuConfig.fp32, ScpuConfig.fp64); _ <- 0 until Seeds.cases(4000)) {
      val model = new BroadPhaseModel(cfg)
      val v = rng.nextInt(4) match {
        case 0 => (rng.nextDouble() - 0.5) * 1e6
        case 1 => (rng.nextInt(2001) - 1000).toDouble // on a face
        case 2 => (rng.nextDouble() - 0.5) * 1e-40
        case _ => math.nextUp((rng.nextInt(201) - 100).toDouble)
      }
      val level = rng.nextInt(120) - 60
      val odd = (level & 1) != 0
      val k = if (odd) (level - 1) / 2 - 1 else level / 2 // the edge is 2^k, or 3 * 2^k
      val vb = ScpuModel.fromDouble(cfg.format, v)
      val exact = new JBigDecimal(ScpuModel.toDouble(cfg.format, vb))
      val scaled = if (k >= 0) exact.divide(new JBigDecimal(BigInt(2).pow(k).bigInteger)) else exact.multiply(new JBigDecimal(BigInt(2).pow(-k).bigInteger))
      val want = scaled.divide(JBigDecimal.valueOf(if (odd) 3 else 1), 0, JRoundingMode.FLOOR).longValueExact()
      assert(model.cell(vb, level).contains(want), s"${cfg.name}: floor($v / ${BroadPhaseParams.edge(level)}) (level $level)")
    }
  }

  it should "grow its work about linearly with spheres at fixed density (sub-quadratic)" in {
    val rng = Seeds.rng("BroadPhaseModelSpec-scale")
    val model = new BroadPhaseModel(ScpuConfig.fp32)
    def perSphere(n: Int) = {
      val r = model.run(bits(FloatFormat.fp32, uniform(rng, n)))
      val cy = model.cycles(r, lanes = 1, scpus = 16)
      (r.stats.scanned.toDouble / n, r.stats.candidates.toDouble / n, cy.generate.toDouble / n)
    }
    val (s1, c1, g1) = perSphere(1000); val (s2, c2, g2) = perSphere(8000)
    println(f"[BroadPhaseModelSpec] per sphere at 1000 / 8000: scanned $s1%.2f / $s2%.2f, candidates $c1%.2f / $c2%.2f, lane cycles $g1%.2f / $g2%.2f")
    // All pairs would multiply each by 8; a grid keeps them within rounding of constant.
    assert(s2 / s1 < 1.5 && c2 / c1 < 1.5 && g2 / g1 < 1.5)
  }
}
