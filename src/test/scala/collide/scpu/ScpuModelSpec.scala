package collide.scpu

import java.math.{BigDecimal => JBigDecimal}
import scala.util.chaining._
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp._
import collide.fp.model._
import collide.scpu.model._
import collide.testutil.Seeds

/** Bounds the properties check, per configuration; docs/scpu.md states them. Units: u is the
  * compute format's ulp of 1, 2^-(sigBits-1).
  */
object ScpuBounds {
  /** ||n| - 1| <= normalUlps * u for contacts whose d2 raised neither OF nor UF (always, for
    * Robust). Measured maxima are in bench/scpu-accuracy.md. */
  def normalUlps(cfg: ScpuConfig): Double = cfg.sqrtAlg match {
    case RootAlgorithm.DigitRecurrence if cfg.distance != DistanceMethod.Rsqrt => 2.0
    case _ => 3.0
  }
  /** The hit decision equals exact arithmetic's except where |d - (r1+r2)| <=
    * bandUlps * u * max(d, |r1+r2|) + 2 * (smallest subnormal), d the exact distance. */
  def bandUlps(cfg: ScpuConfig): Int = 4
}

class ScpuModelSpec extends AnyFlatSpec {
  behavior of "ScpuModel"

  private def isNaN(f: FloatFormat, b: BigInt) = SoftFloat.decode(FpParams(f), b).isInstanceOf[Decoded.NaN]
  private def isInf(f: FloatFormat, b: BigInt) = SoftFloat.decode(FpParams(f), b).isInstanceOf[Decoded.Inf]
  private def neg(f: FloatFormat, b: BigInt) = if (isNaN(f, b)) b else b ^ f.signBit

  /** The pairs every property runs on, per configuration: the hard cases, the mixed and the
    * wide-range random distributions, each pair with its golden trace. */
  private val cache = scala.collection.mutable.Map.empty[String, IndexedSeq[(String, ScpuPair, ScpuTrace)]]
  private def dataset(cfg: ScpuConfig): IndexedSeq[(String, ScpuPair, ScpuTrace)] = cache.getOrElseUpdate(cfg.name, {
    val rng = Seeds.rng(s"ScpuModelSpec-${cfg.name}")
    val v = new ScpuVectors(cfg)
    val model = ScpuModel(cfg)
    val n = Seeds.cases(4000)
    val pairs = v.hardCases ++ v.linkCases ++
      Seq.tabulate(n)(i => s"mixed $i" -> v.mixed(rng)) ++ Seq.tabulate(n)(i => s"wide-range $i" -> v.wideRange(rng))
    pairs.map { case (l, p) => (l, p, model.trace(p)) }.toIndexedSeq
  })

  private val u = (cfg: ScpuConfig) => math.pow(2, -(cfg.format.sigBits - 1))

  // --- The independent oracle ------------------------------------------------------------

  it should "equal plain JVM float arithmetic bit for bit for the fp32 correctly rounded RNE preset" in {
    val cfg = ScpuConfig.fp32
    val rng = Seeds.rng("ScpuModelSpec-oracle")
    val v = new ScpuVectors(cfg)
    val model = ScpuModel(cfg)
    val n = Seeds.cases(20000)
    val pairs = v.hardCases ++ v.linkCases ++ Seq.tabulate(n)(i => s"mixed $i" -> v.mixed(rng)) ++
      Seq.tabulate(n / 4)(i => s"wide-range $i" -> v.wideRange(rng)) ++ Seq.tabulate(n / 4)(i => s"raw $i" -> v.rawLink(rng))
    var hits = 0
    for ((label, p) <- pairs) {
      val r = model.collide(p)
      val o = FloatOde.collide(p)
      assert(FloatOde.agrees(r, o), s"$label: $p\n  model  ${r.show}\n  oracle $o")
      if (r.hit) hits += 1
    }
    info(s"${pairs.size} pairs, $hits hits")
    assert(hits > pairs.size / 5 && hits < pairs.size * 4 / 5, "the distribution should mix hits and misses")
  }

  // --- Properties, every preset ------------------------------------------------------------

  for (cfg <- ScpuConfig.all) {
    val lf = cfg.linkFormat
    val lp = cfg.linkParams

    it should s"report contacts with depth between 0 and r1 + r2 for ${cfg.name}" in {
      var n = 0
      for ((label, p, t) <- dataset(cfg) if t.result.hit && !isNaN(lf, t.result.depth)) {
        val rsInf = isInf(cfg.format, t.rs.bits)
        SoftFloat.toBigDecimal(lp, t.result.depth) match {
          case None => assert(rsInf && !t.result.depth.testBit(lf.width - 1), s"$label: infinite depth with finite r1+r2: ${t.result.show}")
          case Some(depth) =>
            assert(depth >= 0, s"$label: negative depth $depth: ${t.result.show}")
            if (!rsInf) {
              val rs = SoftFloat.toBigDecimal(cfg.params, t.rs.bits).get
              assert(depth <= rs, s"$label: depth $depth above r1+r2 = $rs: ${t.result.show}")
              n += 1
            }
        }
      }
      info(s"$n contacts checked")
      assert(n > 500)
    }

    it should s"keep the normal's length within ${ScpuBounds.normalUlps(cfg)} ulps of 1 for ${cfg.name}" in {
      val bound = ScpuBounds.normalUlps(cfg) * u(cfg)
      var worst = 0.0; var n = 0; var outside = 0
      for ((label, p, t) <- dataset(cfg) if t.result.kind == ContactKind.Contact && !t.result.nonFinite) {
        val r = t.result
        val rangeFlags = t.dx.flags | t.dy.flags | t.dz.flags | t.rs.flags | t.dist.d.flags
        val clean = (rangeFlags & FpFlags.Overflow) == 0 && (cfg.distance == DistanceMethod.Robust ||
          (t.dist.d2.flags & (FpFlags.Underflow | FpFlags.Overflow)) == 0)
        val m = ScpuExact.normSqMinusOne(lp, Seq(r.nx, r.ny, r.nz))
        if (clean) {
          assert(m.isDefined, s"$label: non-finite normal ${r.show}")
          // | |n| - 1 | = | |n|^2 - 1 | / (|n| + 1), to first order half of it.
          val e = math.abs(m.get.doubleValue) / 2
          worst = math.max(worst, e)
          assert(e <= bound, s"$label: | |n| - 1 | = ${e / u(cfg)} ulps > ${ScpuBounds.normalUlps(cfg)}: ${r.show}")
          n += 1
        } else {
          // The documented exception: d2 overflowed or underflowed, or a true value left the
          // format's range (see docs/scpu.md).
          outside += 1
        }
      }
      info(f"$n contacts, worst | |n| - 1 | = ${worst / u(cfg)}%.3f ulps; $outside with d2 UF/OF not bounded")
      assert(n > 500)
    }

    it should s"negate the normal and keep the depth when the spheres swap for ${cfg.name}" in {
      val model = ScpuModel(cfg)
      for ((label, p, t) <- dataset(cfg)) {
        val a = t.result
        val b = model.collide(p.swapped)
        assert(a.hit == b.hit && a.kind == b.kind, s"$label: ${a.show} vs swapped ${b.show}")
        assert(a.depth == b.depth || (isNaN(lf, a.depth) && isNaN(lf, b.depth)), s"$label: depth ${a.show} vs swapped ${b.show}")
        val na = Seq(a.nx, a.ny, a.nz); val nb = Seq(b.nx, b.ny, b.nz)
        // Negated as values: a zero component stays +0 both ways (x - x = +0 in RNE).
        def same(x: BigInt, y: BigInt) = x == y || (isNaN(lf, x) && isNaN(lf, y)) || ((x | lf.signBit) == lf.signBit && (y | lf.signBit) == lf.signBit)
        if (a.kind == ContactKind.Contact) assert(na.map(neg(lf, _)).zip(nb).forall { case (x, y) => same(x, y) }, s"$label: normal ${a.show} vs swapped ${b.show}")
        else assert(na == nb, s"$label: ${a.show} vs swapped ${b.show}")
      }
    }

    val band = ScpuBounds.bandUlps(cfg)
    it should s"decide hits as exact arithmetic does outside $band ulps of grazing for ${cfg.name}" in {
      val rel = ScpuExact.pow2(-(cfg.format.sigBits - 1)).multiply(new JBigDecimal(band))
      val abs = ScpuExact.pow2(cfg.format.minSubExp + 1)
      var inBand = 0; var mism = 0; var pinned = 0; var n = 0
      for ((label, p, t) <- dataset(cfg); ex <- ScpuExact.decision(cfg.params, t.inputs)) {
        n += 1
        val got = t.result.hit
        // Robust and every other config: overflow of the difference, of r1 + r2, or of d in
        // the true values is outside any format's reach; non-robust: d2's own OF/UF too.
        val rangeFlags = t.dx.flags | t.dy.flags | t.dz.flags | t.rs.flags | t.dist.d.flags
        val outOfRange = (rangeFlags & FpFlags.Overflow) != 0 ||
          (cfg.distance != DistanceMethod.Robust && (t.dist.d2.flags & (FpFlags.Underflow | FpFlags.Overflow)) != 0)
        if (got != ex.hit) {
          if (ex.within(rel, abs)) inBand += 1
          else if (outOfRange) pinned += 1
          else { mism += 1; assert(false, s"$label: hit $got, exact ${ex.hit} (d2 ${ex.d2}, rs ${ex.rs}): ${t.result.show}") }
        }
      }
      info(s"$n pairs: $inBand disagreements inside the band, $pinned where d2 (or the difference, r1+r2) left the range")
    }

    if (cfg.distance == DistanceMethod.Robust) {
      it should s"never report NaN or infinite contact fields for finite inputs within range for ${cfg.name}" in {
        val rng = Seeds.rng(s"ScpuModelSpec-robust-${cfg.name}")
        val v = new ScpuVectors(cfg)
        val model = ScpuModel(cfg)
        var hits = 0
        val pairs = v.hardCases.filter { case (l, _) => !l.contains("NaN") && !l.contains("inf") &&
          !l.contains("sum overflows") && !l.contains("difference overflows") && !l.contains("largest finite") } ++ Seq.tabulate(Seq(4000, Seeds.cases(4000)).max)(i => s"wide-range $i" -> v.wideRange(rng))
        for ((label, p) <- pairs) {
          val r = model.collide(p)
          assert(!r.nonFinite, s"$label: generator gave a non-finite input")
          if (r.hit) {
            hits += 1
            assert(r.fields.forall(b => !isNaN(lf, b) && !isInf(lf, b)), s"$label: ${r.show}")
          }
        }
        info(s"${pairs.size} pairs, $hits hits, all fields finite")
        assert(hits > pairs.size / 4)
      }
    }
  }

  // --- Pinned behaviour at the edges of the range ------------------------------------------

  private def run(cfg: ScpuConfig, label: String): ScpuTrace = {
    val v = new ScpuVectors(cfg)
    val p = (v.hardCases ++ v.linkCases).find(_._1 == label).getOrElse(fail(s"no hard case '$label'"))._2
    ScpuModel(cfg).trace(p)
  }

  it should "report no contact, with OF, when d2 overflows in fp16 although the radii cover the distance" in {
    val t = run(ScpuConfig.fp16, "squared distance overflows, radii cover it")
    assert(ScpuExact.decision(ScpuConfig.fp16.params, t.inputs).get.hit, "the exact decision is a contact")
    assert(!t.result.hit && t.result.kind == ContactKind.Separated && (t.result.flags & FpFlags.Overflow) != 0, t.result.show)
    assert(t.result.fields.forall(_ == 0))
  }

  it should "report the contact with a unit normal when d2 would overflow in fp16-robust" in {
    val cfg = ScpuConfig.fp16Robust
    val t = run(cfg, "squared distance overflows, radii cover it")
    val r = t.result
    assert(r.hit && r.kind == ContactKind.Contact && (r.flags & FpFlags.Overflow) == 0, r.show)
    val lf = cfg.linkFormat
    assert(math.abs(ScpuModel.toDouble(lf, r.nx) - 1) <= math.pow(2, -10) && r.ny == 0 && r.nz == 0, r.show)
    assert(r.fields.forall(b => !isNaN(lf, b) && !isInf(lf, b)), r.show)
  }

  it should "report coincident centres, with UF, when d2 underflows to zero without Robust" in {
    for (cfg <- Seq(ScpuConfig.fp32, ScpuConfig.fp16)) {
      val t = run(cfg, "separation whose square underflows to zero, radii smaller")
      assert(!ScpuExact.decision(cfg.params, t.inputs).get.hit, "the exact decision is no contact")
      val r = t.result
      assert(r.hit && r.kind == ContactKind.Coincident && (r.flags & FpFlags.Underflow) != 0, s"${cfg.name}: ${r.show}")
      assert(r.nx == ScpuModel.fromDouble(cfg.linkFormat, 1.0) && r.depth == t.rs.bits.pipe(b => new ScpuVectors(cfg).link(b)))
    }
  }

  it should "decide the underflowing separation exactly and give the true normal with Robust" in {
    for (cfg <- Seq(ScpuConfig.fp32Robust, ScpuConfig.fp16Robust)) {
      val miss = run(cfg, "separation whose square underflows to zero, radii smaller").result
      assert(!miss.hit, s"${cfg.name}: ${miss.show}")
      val hit = run(cfg, "separation whose square underflows to zero, radii larger").result
      assert(hit.hit && hit.kind == ContactKind.Contact && hit.nx == ScpuModel.fromDouble(cfg.linkFormat, 1.0), s"${cfg.name}: ${hit.show}")
    }
  }

  it should "give an infinite depth and NaN position and normal when d = r1 + r2 = inf (difference and radii overflow)" in {
    for (cfg <- ScpuConfig.all) {
      val r = run(cfg, "difference overflows and radii sum overflows").result
      val lf = cfg.linkFormat
      // d = inf <= rs = inf: ODE's formula then gives depth inf - inf and normal inf * 0.
      assert(r.hit && r.kind == ContactKind.Contact && isNaN(lf, r.depth) && isNaN(lf, r.nx), s"${cfg.name}: ${r.show}")
      assert((r.flags & (FpFlags.Overflow | FpFlags.Invalid)) == (FpFlags.Overflow | FpFlags.Invalid), s"${cfg.name}: ${r.show}")
      assert(!r.nonFinite)
    }
  }

  it should "follow ODE on the hard cases every preset shares" in {
    for (cfg <- ScpuConfig.all) {
      val lf = cfg.linkFormat
      val one = ScpuModel.fromDouble(lf, 1.0)
      def r(l: String) = run(cfg, l).result
      // Touching spheres are a contact of depth 0 (the paper's design missed them).
      for (l <- Seq("exact grazing (3,4,0) r1=2 r2=3", "grazing along an axis, r1 = r2", "grazing scaled (6,8,0) r1=4 r2=6 offset")) {
        val g = r(l)
        assert(g.hit && g.kind == ContactKind.Contact && g.depth == 0, s"${cfg.name} $l: ${g.show}")
      }
      assert(r("grazing with r2 one ulp larger").kind == ContactKind.Contact, cfg.name)
      assert(r("grazing with x one ulp nearer").kind == ContactKind.Contact, cfg.name)
      for (l <- Seq("coincident centres", "+0 versus -0 coordinates", "coincident centres at the origin, zero radii")) {
        val c = r(l)
        assert(c.hit && c.kind == ContactKind.Coincident && c.nx == one && c.ny == 0 && c.nz == 0, s"${cfg.name} $l: ${c.show}")
      }
      val z = r("coincident centres at the origin, zero radii")
      assert(z.depth == 0 && z.px == 0, s"${cfg.name}: ${z.show}")
      assert(!r("zero radii, distinct centres").hit && !r("negative radii").hit, cfg.name)
      assert(r("centres one ulp apart in x").kind == ContactKind.Contact, cfg.name)
      for (nm <- Seq("quiet NaN", "signaling NaN"); i <- 0 until 8) {
        val x = r(s"$nm in field $i")
        assert(!x.hit && x.nonFinite && x.fields.forall(_ == 0), s"${cfg.name} $nm $i: ${x.show}")
        assert(((x.flags & FpFlags.Invalid) != 0) == (nm == "signaling NaN"), s"${cfg.name} $nm $i: ${x.show}")
      }
      for (i <- Seq(0, 1, 2, 4, 5, 6)) assert(!r(s"+inf in field $i").hit && r(s"+inf in field $i").nonFinite, s"${cfg.name} inf $i")
      // An infinite radius covers any finite distance: a contact of infinite depth, NaN position.
      val infR = r("infinite radii at finite distance")
      assert(infR.hit && infR.kind == ContactKind.Contact && isInf(lf, infR.depth) && infR.nonFinite, s"${cfg.name}: ${infR.show}")
    }
  }

  it should "count only the flags of the path that fired" in {
    val cfg = ScpuConfig.fp32
    // Coincident centres: 1/d would raise DZ, but the coincident path does not use it.
    val c = run(cfg, "coincident centres").result
    assert(c.kind == ContactKind.Coincident && c.flags == 0, c.show)
    // Exact grazing: every operation exact but 1/5 (and the products that use it).
    assert(run(cfg, "exact grazing (3,4,0) r1=2 r2=3").result.flags == FpFlags.Inexact)
    // A signaling NaN raises NV in the first operator that reads it.
    assert((run(cfg, "signaling NaN in field 0").result.flags & FpFlags.Invalid) != 0)
    // fp16 on a binary32 link: converting a value beyond fp16's range overflows. (On its
    // own binary16 link the host rounds it to infinity before the AFU sees it: non-finite.)
    val ov = run(ScpuConfig.fp16.copy(name = "fp16-link32", link = Some(FloatFormat.fp32)), "inputs beyond the compute range").result
    assert((ov.flags & FpFlags.Overflow) != 0 && !ov.nonFinite && !ov.hit, ov.show)
    val ov16 = run(ScpuConfig.fp16, "inputs beyond the compute range").result
    assert(ov16.nonFinite && !ov16.hit, ov16.show)
  }

  it should "equal OdeReference in double for the fp64 correctly rounded preset" in {
    val cfg = ScpuConfig.fp64
    val rng = Seeds.rng("ScpuModelSpec-fp64-double")
    val v = new ScpuVectors(cfg)
    val model = ScpuModel(cfg)
    for ((label, p) <- v.hardCases ++ Seq.tabulate(Seeds.cases(3000))(i => s"mixed $i" -> v.mixed(rng))) {
      val d = p.fields.map(b => java.lang.Double.longBitsToDouble(b.toLong))
      val o = OdeReference.collide(V3(d(0), d(1), d(2)), d(3), V3(d(4), d(5), d(6)), d(7))
      val r = model.collide(p)
      val got = r.fields.map(b => java.lang.Double.longBitsToDouble(b.toLong))
      val want = Seq(o.pos.x, o.pos.y, o.pos.z, o.normal.x, o.normal.y, o.normal.z, o.depth)
      assert(r.hit == o.hit && r.kind == o.kind && got.zip(want).forall { case (a, b) => (a.isNaN && b.isNaN) || java.lang.Double.doubleToRawLongBits(a) == java.lang.Double.doubleToRawLongBits(b) },
        s"$label: ${r.show} vs $o")
    }
  }
}
