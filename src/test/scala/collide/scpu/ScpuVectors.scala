package collide.scpu

import scala.util.Random
import collide.fp._
import collide.scpu.model._

/** Pair generators for the SCPU specs and the accuracy report, per configuration. Values are
  * built in the compute format (so "a few ulps from grazing" means the compute format's ulps)
  * and carried in the link format, except where a case is about the link -> compute rounding.
  */
final class ScpuVectors(cfg: ScpuConfig) {
  val f: FloatFormat  = cfg.format
  val lf: FloatFormat = cfg.linkFormat
  private val p  = FpParams(f)
  private val fp64 = FloatFormat.fp64

  // Compute-format values and their link-format carriers.
  /** A double rounded to the compute format (RNE), as a compute-format bit pattern. */
  def c(v: Double): BigInt = ScpuModel.fromDouble(f, v)
  /** A compute-format bit pattern widened to the link format (exact). */
  def link(bits: BigInt): BigInt =
    if (f == lf) bits else collide.fp.model.FpConvertModel(p, FpParams(lf), bits, RoundingMode.RNE).bits
  def value(bits: BigInt): Double = ScpuModel.toDouble(f, bits)
  /** A pair from compute-format bit patterns. */
  def pairC(xs: Seq[BigInt], tag: BigInt = 0): ScpuPair = ScpuPair.fromFields(xs.map(link), tag)
  /** A pair from doubles, each rounded to the compute format. */
  def pairD(xs: Double*): ScpuPair = pairC(xs.map(c))

  /** The k-th neighbour of a finite compute-format value (k ulps up for k > 0), crossing zero
    * through the other sign's zero as integers order them. */
  def step(bits: BigInt, k: Int): BigInt = {
    val sign = bits.testBit(f.width - 1)
    val mag  = bits & (f.signBit - 1)
    val ordinal = if (sign) -mag else mag
    val o = ordinal + k
    if (o < 0) f.signBit | (-o) else o
  }
  def ulp(bits: BigInt): Double = math.abs(value(step(bits & (f.signBit - 1), 1)) - value(bits & (f.signBit - 1)))

  val maxF: Double    = value(f.maxFinite(false))
  val minNormal: Double = math.pow(2, f.minExp)
  val minSub: Double  = math.pow(2, f.minSubExp)
  val inf: BigInt     = f.infinity(false)
  val negInf: BigInt  = f.infinity(true)
  val qnan: BigInt    = f.canonicalNaN
  val snan: BigInt    = f.infinity(false) | 1
  val negZero: BigInt = f.signBit
  /** Largest |component| whose square stays finite, about sqrt(maxF). */
  val sqrtMax: Double = math.sqrt(maxF)

  private def unit(rng: Random): (Double, Double, Double) = {
    var v = (0.0, 0.0, 0.0); var n = 0.0
    while (n < 1e-3 || n > 1) { v = (rng.nextDouble() * 2 - 1, rng.nextDouble() * 2 - 1, rng.nextDouble() * 2 - 1); n = v._1 * v._1 + v._2 * v._2 + v._3 * v._3 }
    val s = math.sqrt(n); (v._1 / s, v._2 / s, v._3 / s)
  }
  private def signed(rng: Random, x: Double) = if (rng.nextBoolean()) x else -x
  /** A magnitude scale that keeps squares of coordinate differences well inside the format. */
  private val typical: Double = math.min(100.0, sqrtMax / 8)

  /** Uniform: centres in a cube of side `typical`, radii up to typical/4 (about a third hit). */
  def uniform(rng: Random): ScpuPair = {
    def coord = (rng.nextDouble() * 2 - 1) * typical / 2
    def rad = rng.nextDouble() * typical / 4
    pairD(coord, coord, coord, rad, coord, coord, coord, rad)
  }

  /** Clustered within a few ulps of grazing: |p1 - p2| = r1 + r2 in exact arithmetic up to the
    * rounding of the centres, then r2 moved by -4..4 ulps. */
  def grazing(rng: Random): ScpuPair = {
    val scale = math.pow(2, rng.nextInt(9) - 4) * typical / 8
    val (ux, uy, uz) = rng.nextInt(4) match {
      case 0 => (1.0, 0.0, 0.0)          // axis-aligned: the difference is exact more often
      case 1 => (0.6, 0.8, 0.0)          // a 3-4-5 direction
      case _ => unit(rng)
    }
    val r1 = c(rng.nextDouble() * scale)
    val r2 = c(rng.nextDouble() * scale)
    val dist = value(r1) + value(r2)
    val (x1, y1, z1) = ((rng.nextDouble() - 0.5) * typical, (rng.nextDouble() - 0.5) * typical, (rng.nextDouble() - 0.5) * typical)
    val p1 = Seq(x1, y1, z1).map(c)
    val p2 = Seq(value(p1(0)) - ux * dist, value(p1(1)) - uy * dist, value(p1(2)) - uz * dist).map(c)
    pairC(p1 ++ Seq(r1) ++ p2 ++ Seq(step(r2, rng.nextInt(9) - 4)))
  }

  /** Large coordinates (near the top of the range a format's squares allow) with small gaps
    * between the spheres, a few ulps of the coordinates wide. */
  def largeSmallGap(rng: Random): ScpuPair = {
    val big = math.min(1e6, sqrtMax / 4) * (0.5 + rng.nextDouble())
    val x1 = c(signed(rng, big)); val y1 = c(signed(rng, big) * rng.nextDouble()); val z1 = c(signed(rng, big) * rng.nextDouble())
    val (ux, uy, uz) = unit(rng)
    val gapUlps = rng.nextInt(200) + 1
    val dist = ulp(x1) * gapUlps
    val r1 = c(dist * rng.nextDouble() * 0.7); val r2 = c(dist * rng.nextDouble() * 0.7)
    val p2 = Seq(value(x1) - ux * dist, value(y1) - uy * dist, value(z1) - uz * dist).map(c)
    pairC(Seq(x1, y1, z1, r1) ++ p2 ++ Seq(r2))
  }

  /** Any scale the format holds: the separation's exponent drawn across the whole range
    * (subnormal to a quarter of the largest finite), centres near the separation's scale or
    * far larger, radii summing to 0.5..1.5 times the separation. Every value stays below
    * maxFinite/4, so differences, sums, positions and depths cannot overflow in exact
    * arithmetic: the domain of the Robust method's no-NaN/no-inf property. */
  def wideRange(rng: Random): ScpuPair = {
    val lo = f.minSubExp + 2; val hi = f.maxExp - 3
    val e = lo + rng.nextInt(hi - lo + 1)
    val dist = math.pow(2, e) * (1 + rng.nextDouble())
    val (ux, uy, uz) = rng.nextInt(3) match {
      case 0 => (1.0, 0.0, 0.0)
      case _ => unit(rng)
    }
    val cap = maxF / 4
    val centreScale = math.min(cap / 2, if (rng.nextBoolean()) dist else dist * math.pow(2, rng.nextInt(f.sigBits + 2)))
    def clamp(v: Double) = math.max(-cap, math.min(cap, v))
    val p1 = Seq.fill(3)(c(clamp((rng.nextDouble() * 2 - 1) * centreScale)))
    val p2 = Seq(value(p1(0)) - ux * dist, value(p1(1)) - uy * dist, value(p1(2)) - uz * dist).map(v => c(clamp(v)))
    val sum = dist * (0.5 + rng.nextDouble())
    val share = rng.nextDouble()
    val r1 = c(math.min(cap, sum * share)); val r2 = c(math.min(cap, sum * (1 - share)))
    pairC(p1 ++ Seq(r1) ++ p2 ++ Seq(r2))
  }

  /** A mix of the three distributions, each a third. */
  def mixed(rng: Random): ScpuPair = rng.nextInt(3) match {
    case 0 => uniform(rng)
    case 1 => grazing(rng)
    case _ => largeSmallGap(rng)
  }

  /** Raw random link-format patterns (specials, edges, anything): exercises conversion and
    * the special-value paths. */
  def rawLink(rng: Random): ScpuPair =
    ScpuPair.fromFields(Seq.fill(8)(collide.testutil.FpPatterns.operand(lf, rng)))

  /** The hard cases of docs/scpu.md ("Hard cases") and more, with a label each. */
  def hardCases: Seq[(String, ScpuPair)] = {
    val one = c(1.0); val zero = BigInt(0)
    val g = Seq.newBuilder[(String, ScpuPair)]
    def add(label: String, xs: BigInt*): Unit = g += label -> pairC(xs)
    // Coincident centres.
    add("coincident centres", one, c(2), c(3), one, one, c(2), c(3), one)
    add("coincident centres at the origin, zero radii", zero, zero, zero, zero, zero, zero, zero, zero)
    add("coincident centres, one zero radius", c(5), zero, zero, zero, c(5), zero, zero, c(0.5))
    // Signed zeros.
    add("+0 versus -0 coordinates", zero, zero, zero, one, negZero, negZero, negZero, one)
    add("-0 versus +0 coordinates", negZero, negZero, negZero, one, zero, zero, zero, one)
    add("-0 radii at coincident centres", zero, zero, zero, negZero, zero, zero, zero, negZero)
    // One ulp apart.
    add("centres one ulp apart in x", one, c(2), c(3), c(0.25), step(one, 1), c(2), c(3), c(0.25))
    add("centres one ulp apart in every axis", one, one, one, c(0.5), step(one, -1), step(one, -1), step(one, -1), c(0.5))
    add("centres one ulp apart at a large coordinate", c(typical * 64), zero, zero, c(0.5), step(c(typical * 64), 1), zero, zero, c(0.5))
    // Squares underflow.
    val tinyDiff = math.pow(2, (f.minExp - f.fracBits) / 2 - 1)  // square below the smallest subnormal
    val smallDiff = math.pow(2, f.minExp / 2 - 2)                 // square subnormal
    add("separation whose square underflows to zero, radii larger", c(tinyDiff), zero, zero, c(tinyDiff * 4), zero, zero, zero, c(tinyDiff * 4))
    add("separation whose square underflows to zero, radii smaller", c(tinyDiff), zero, zero, c(tinyDiff / 8), zero, zero, zero, c(tinyDiff / 8))
    add("separation whose square underflows to zero, zero radii", c(tinyDiff), zero, zero, zero, zero, zero, zero, zero)
    add("separation whose square is subnormal, contact", c(smallDiff), c(smallDiff), zero, c(smallDiff), zero, zero, zero, c(smallDiff))
    add("separation whose square is subnormal, no contact", c(smallDiff * 3), c(smallDiff), zero, c(smallDiff / 4), zero, zero, zero, c(smallDiff / 4))
    // Subnormals.
    val sub = BigInt(3); val sub2 = BigInt(1)
    add("subnormal coordinates and radii, contact", sub, zero, zero, sub, sub2, zero, zero, sub)
    add("subnormal coordinates and radii, no contact", f.fracMask, zero, zero, sub2, zero, zero, zero, sub2)
    add("subnormal radii at ordinary centres", one, zero, zero, sub, c(0.5), zero, zero, sub)
    add("largest subnormal against smallest normal", f.fracMask, zero, zero, sub2, BigInt(1) << f.fracBits, zero, zero, sub2)
    // d2 overflow (fp32 |diff| about 2e19, fp16 about 300).
    val ov = sqrtMax * 1.5
    add("squared distance overflows, radii cover it", c(ov / 2), zero, zero, c(ov * 0.6), c(-ov / 2), zero, zero, c(ov * 0.6))
    add("squared distance overflows, radii do not cover it", c(ov / 2), zero, zero, c(ov * 0.4), c(-ov / 2), zero, zero, c(ov * 0.4))
    add("squared distance overflows in three axes", c(ov / 2), c(ov / 2), c(ov / 2), c(ov * 0.9), c(-ov / 2), c(-ov / 2), c(-ov / 2), c(ov * 0.9))
    add("squared distance just below overflow", c(sqrtMax * 0.7), zero, zero, c(sqrtMax * 0.4), zero, c(sqrtMax * 0.7), zero, c(sqrtMax * 0.4))
    // Exact grazing: diff (3,4,0), r1 = 2, r2 = 3: contact of depth 0, and one ulp either side.
    add("exact grazing (3,4,0) r1=2 r2=3", c(3), c(4), zero, c(2), zero, zero, zero, c(3))
    add("grazing with r2 one ulp smaller", c(3), c(4), zero, c(2), zero, zero, zero, step(c(3), -1))
    add("grazing with r2 one ulp larger", c(3), c(4), zero, c(2), zero, zero, zero, step(c(3), 1))
    add("grazing with x one ulp further", step(c(3), 1), c(4), zero, c(2), zero, zero, zero, c(3))
    add("grazing with x one ulp nearer", step(c(3), -1), c(4), zero, c(2), zero, zero, zero, c(3))
    add("grazing along an axis, r1 = r2", c(2), zero, zero, one, zero, zero, zero, one)
    add("grazing scaled (6,8,0) r1=4 r2=6 offset", c(7), c(9), c(1), c(4), one, one, one, c(6))
    // Large coordinates, small gap.
    val big = c(math.min(1e6, sqrtMax / 4))
    add("large coordinates touching", big, zero, zero, c(value(step(big, 2)) - value(big)), step(big, 4), zero, zero, c(value(step(big, 4)) - value(step(big, 2))))
    add("large coordinates one ulp gap", big, big, zero, zero, step(big, 1), big, zero, zero)
    add("large coordinates on opposite sides of zero", c(typical * 8), zero, zero, c(typical * 8), c(-typical * 8), zero, zero, c(typical * 8))
    // Large radii near grazing.
    val bigR = c(math.min(1e5, sqrtMax / 8))
    add("large radii exactly grazing", c(2 * value(bigR)), zero, zero, bigR, zero, zero, zero, bigR)
    add("large radii one ulp short of grazing", c(2 * value(bigR)), zero, zero, step(bigR, -1), zero, zero, zero, bigR)
    add("large radii one ulp past grazing", c(2 * value(bigR)), zero, zero, step(bigR, 1), zero, zero, zero, bigR)
    // Huge radius ratios.
    val hugeR = c(math.min(1e30, sqrtMax / 16)); val tinyR = c(math.max(1e-30, minNormal * 4))
    add("huge radius ratio, contact", one, zero, zero, tinyR, zero, zero, zero, hugeR)
    add("huge radius ratio, small sphere outside", c(value(hugeR) * 2), zero, zero, tinyR, zero, zero, zero, hugeR)
    add("huge radius ratio reversed", one, zero, zero, hugeR, zero, zero, zero, tinyR)
    // Zero radii.
    add("zero radii, distinct centres", one, zero, zero, zero, zero, zero, zero, zero)
    add("zero radii, equal centres", one, one, one, zero, one, one, one, zero)
    // Radii overflow / difference overflow (finite inputs).
    val mx = f.maxFinite(false)
    add("radii sum overflows, centres apart", one, zero, zero, mx, zero, zero, zero, mx)
    add("difference overflows and radii sum overflows", mx, zero, zero, mx, f.maxFinite(true), zero, zero, mx)
    add("difference overflows, small radii", mx, zero, zero, one, f.maxFinite(true), zero, zero, one)
    add("largest finite coordinates coincident", mx, mx, mx, one, mx, mx, mx, one)
    // Negative radii (ODE does not check them).
    add("negative radii", one, zero, zero, c(-1), zero, zero, zero, c(-1))
    add("negative radius sum exactly zero at coincident centres", one, zero, zero, c(-1), one, zero, zero, one)
    // Non-finite inputs, as the link carries them (a signaling NaN must reach the SCPU as one).
    val lfmt = lf
    for ((nm, v) <- Seq("quiet NaN" -> lfmt.canonicalNaN, "signaling NaN" -> (lfmt.infinity(false) | 1),
                        "+inf" -> lfmt.infinity(false), "-inf" -> lfmt.infinity(true)); idx <- 0 until 8) {
      val base = Seq(one, c(2), c(3), c(1.5), c(1.5), c(2), c(3), one).map(link).toArray
      base(idx) = v
      g += s"$nm in field $idx" -> ScpuPair.fromFields(base.toIndexedSeq)
    }
    add("infinite radii at finite distance", one, zero, zero, inf, zero, zero, zero, one)
    add("both centres infinite", inf, zero, zero, one, inf, zero, zero, one)
    add("infinite centre and infinite radius", inf, zero, zero, inf, zero, zero, zero, one)
    g.result()
  }

  /** Link-format inputs the compute format cannot hold exactly (conversion rounds, overflows,
    * underflows); only differs from hardCases for formats narrower than the link. */
  def linkCases: Seq[(String, ScpuPair)] = {
    def l(v: Double): BigInt = ScpuModel.fromDouble(lf, v)
    def pr(label: String, v: Double*) = label -> ScpuPair.fromFields(v.map(l))
    Seq(
      pr("inputs that round on conversion", 1.0 + 1e-7, 2.0 / 3, 0.1, 0.7, 0.0, 0.0, 0.0, 0.5),
      pr("inputs beyond the compute range", 1e30, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
      pr("inputs below the compute range", 1e-30, 0.0, 0.0, 1e-30, 0.0, 0.0, 0.0, 1e-30),
      pr("radius beyond the compute range", 0.0, 0.0, 0.0, 1e30, 1.0, 0.0, 0.0, 1.0),
      pr("tie on conversion", 1.0 + math.pow(2, -f.sigBits), 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    )
  }
}
