package collide.scpu.model

import collide.fp._
import collide.fp.model._
import collide.scpu.{ContactKind, DistanceMethod, ScpuConfig}

/** One pair on the SCPU's input: link-format bit patterns (binary32 or binary64) and a tag. */
final case class ScpuPair(x1: BigInt, y1: BigInt, z1: BigInt, r1: BigInt,
                          x2: BigInt, y2: BigInt, z2: BigInt, r2: BigInt, tag: BigInt = 0) {
  def fields: Seq[BigInt] = Seq(x1, y1, z1, r1, x2, y2, z2, r2)
  /** The same pair with the spheres swapped. */
  def swapped: ScpuPair = ScpuPair(x2, y2, z2, r2, x1, y1, z1, r1, tag)
}

object ScpuPair {
  def fromFields(f: Seq[BigInt], tag: BigInt = 0): ScpuPair = {
    require(f.length == 8, s"ScpuPair.fromFields: need 8 fields, got ${f.length}")
    ScpuPair(f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7), tag)
  }
  /** From doubles (rounded to the link format `lf` in RNE, as a host would). */
  def ofDoubles(lf: FloatFormat, v: Seq[Double], tag: BigInt = 0): ScpuPair = fromFields(v.map(ScpuModel.fromDouble(lf, _)), tag)
}

/** One SCPU result, as io.out carries it: link-format bit patterns (zero when !hit). */
final case class ScpuResult(hit: Boolean, kind: Int, px: BigInt, py: BigInt, pz: BigInt,
                            nx: BigInt, ny: BigInt, nz: BigInt, depth: BigInt,
                            nonFinite: Boolean, flags: Int, tag: BigInt, d: BigInt, w: BigInt) {
  def fields: Seq[BigInt] = Seq(px, py, pz, nx, ny, nz, depth)
  /** The derived record's values: d and the normal's factor w (zero unless a Contact). */
  def derived: Seq[BigInt] = Seq(d, w)
  def show: String =
    s"hit=$hit kind=$kind pos=(${px.toString(16)},${py.toString(16)},${pz.toString(16)}) " +
      s"n=(${nx.toString(16)},${ny.toString(16)},${nz.toString(16)}) depth=${depth.toString(16)} " +
      s"d=${d.toString(16)} w=${w.toString(16)} nonFinite=$nonFinite flags=${FpFlags.show(flags)} tag=$tag"
}

/** The compute-format values inside the SCPU for one pair, for tests and reports. */
final case class ScpuTrace(in: Seq[FpResult], dx: FpResult, dy: FpResult, dz: FpResult,
                           rs: FpResult, rdiff: FpResult, dist: DistanceModelOut,
                           le: Boolean, dZero: Boolean, result: ScpuResult) {
  /** Compute-format inputs (after the link -> compute conversion). */
  def inputs: Seq[BigInt] = in.map(_.bits)
}

/** What a distance unit produces: d (with the flags of every operator on its path) and the
  * normal's factors n = (ux,uy,uz) * w (w's flags: those only the contact path uses).
  */
final case class DistanceModelOut(d: FpResult, ux: BigInt, uy: BigInt, uz: BigInt, w: FpResult, d2: FpResult)

/** Golden model of Scpu(cfg), bit for bit (values, kind, flags): the operators' golden models
  * applied in the RTL's order and formats. See docs/scpu.md for which operators' flags count.
  */
final class ScpuModel(val cfg: ScpuConfig) {
  private val p  = cfg.params
  private val lp = cfg.linkParams
  private val f  = cfg.format
  private val rm = cfg.rm

  private def add(a: BigInt, b: BigInt) = FpAddModel(p, a, b, rm, subtract = false)
  private def sub(a: BigInt, b: BigInt) = FpAddModel(p, a, b, rm, subtract = true)
  private def mul(a: BigInt, b: BigInt) = FpMulModel(p, a, b, rm)

  val one: BigInt  = BigInt(f.bias) << f.fracBits
  val half: BigInt = BigInt(f.bias - 1) << f.fracBits

  def convertIn(x: BigInt): FpResult  = if (cfg.converts) FpConvertModel(lp, p, x, rm) else FpResult(x, 0)
  def convertOut(x: BigInt): FpResult = if (cfg.converts) FpConvertModel(p, lp, x, rm) else FpResult(x, 0)

  /** Sum of squares in ODE's order: (dx*dx + dy*dy) + dz*dz. */
  def sumOfSquares(dx: BigInt, dy: BigInt, dz: BigInt): FpResult = {
    val sx = mul(dx, dx); val sy = mul(dy, dy); val sz = mul(dz, dz)
    val s  = add(sx.bits, sy.bits)
    val d2 = add(s.bits, sz.bits)
    FpResult(d2.bits, sx.flags | sy.flags | sz.flags | s.flags | d2.flags)
  }

  def distance(dx: BigInt, dy: BigInt, dz: BigInt): DistanceModelOut = cfg.distance match {
    case DistanceMethod.SqrtThenRecip =>
      val d2 = sumOfSquares(dx, dy, dz)
      val d  = FpSqrtModel(p, cfg.sqrtAlg, d2.bits, rm)
      val w  = FpRecipModel(p, cfg.recipAlg, d.bits, rm)
      DistanceModelOut(FpResult(d.bits, d2.flags | d.flags), dx, dy, dz, w, d2)
    case DistanceMethod.Rsqrt =>
      val d2  = sumOfSquares(dx, dy, dz)
      val inv = FpRsqrtModel(p, cfg.rsqrtAlg, d2.bits, rm)
      val dm  = mul(d2.bits, inv.bits)
      // sqrt(0) = 0 and sqrt(inf) = inf exactly: d2 * rsqrt(d2) would give 0 * inf = NaN.
      val guard = SoftFloat.decode(p, d2.bits) match {
        case Decoded.Zero(_) | Decoded.Inf(_) => true
        case _                                => false
      }
      val d = if (guard) FpResult(d2.bits, d2.flags) else FpResult(dm.bits, d2.flags | inv.flags | dm.flags)
      DistanceModelOut(d, dx, dy, dz, inv, d2)
    case DistanceMethod.Robust =>
      val e  = ScpuModel.scaleExponent(p, Seq(dx, dy, dz))
      val sx = ScpuModel.pow2Scale(p, dx, -e, rm)
      val sy = ScpuModel.pow2Scale(p, dy, -e, rm)
      val sz = ScpuModel.pow2Scale(p, dz, -e, rm)
      val d2 = sumOfSquares(sx.bits, sy.bits, sz.bits)
      val ds = FpSqrtModel(p, cfg.sqrtAlg, d2.bits, rm)
      val d  = ScpuModel.pow2Scale(p, ds.bits, e, rm)
      val w  = FpRecipModel(p, cfg.recipAlg, ds.bits, rm)
      DistanceModelOut(FpResult(d.bits, sx.flags | sy.flags | sz.flags | d2.flags | ds.flags | d.flags),
        sx.bits, sy.bits, sz.bits, w, FpResult(d2.bits, sx.flags | sy.flags | sz.flags | d2.flags))
  }

  def trace(in: ScpuPair): ScpuTrace = {
    val nonFinite = in.fields.exists(x => SoftFloat.decode(lp, x) match {
      case Decoded.NaN(_) | Decoded.Inf(_) => true
      case _                               => false
    })
    val c = in.fields.map(convertIn)
    val Seq(x1, y1, z1, r1, x2, y2, z2, r2) = c.map(_.bits)
    val dx = sub(x1, x2); val dy = sub(y1, y2); val dz = sub(z1, z2)
    val rs = add(r1, r2)
    val rdiff = sub(r2, r1)
    val dist = distance(dx.bits, dy.bits, dz.bits)
    val d = dist.d.bits
    val cmp = FpCompareModel(p, d, rs.bits)
    val le = cmp.lt || cmp.eq
    val dZero = ScpuModel.notPositive(p, d)
    val baseFlags = c.map(_.flags).reduce(_ | _) | dx.flags | dy.flags | dz.flags | rs.flags | dist.d.flags | cmp.flags

    val (kind, fields, pathFlags) =
      if (!le) (ContactKind.Separated, Seq.fill(9)(BigInt(0)), 0)
      else if (dZero) (ContactKind.Coincident, Seq(x1, y1, z1, one, BigInt(0), BigInt(0), rs.bits, BigInt(0), BigInt(0)), 0)
      else {
        val depth = sub(rs.bits, d)
        val k0 = sub(rdiff.bits, d)
        val k  = mul(half, k0.bits)
        val n  = Seq(dist.ux, dist.uy, dist.uz).map(u => mul(u, dist.w.bits))
        val nk = n.map(ni => mul(ni.bits, k.bits))
        val pos = Seq(x1, y1, z1).zip(nk).map { case (pi, t) => add(pi, t.bits) }
        val fl = (Seq(rdiff, dist.w, depth, k0, k) ++ n ++ nk ++ pos).map(_.flags).reduce(_ | _)
        (ContactKind.Contact, pos.map(_.bits) ++ n.map(_.bits) ++ Seq(depth.bits, d, dist.w.bits), fl)
      }
    val out = fields.map(convertOut)
    val flags = baseFlags | pathFlags | out.map(_.flags).reduce(_ | _)
    val o = out.map(_.bits)
    val res = ScpuResult(le, kind, o(0), o(1), o(2), o(3), o(4), o(5), o(6), nonFinite, flags, in.tag, o(7), o(8))
    ScpuTrace(c, dx, dy, dz, rs, rdiff, dist, le, dZero, res)
  }

  def collide(in: ScpuPair): ScpuResult = trace(in).result

  def collide(x1: BigInt, y1: BigInt, z1: BigInt, r1: BigInt,
              x2: BigInt, y2: BigInt, z2: BigInt, r2: BigInt, tag: BigInt): ScpuResult =
    collide(ScpuPair(x1, y1, z1, r1, x2, y2, z2, r2, tag))
}

object ScpuModel {
  def apply(cfg: ScpuConfig): ScpuModel = new ScpuModel(cfg)

  /** d <= 0 for a d that is never negative: zero of either sign (a negative non-NaN counts too). */
  def notPositive(p: FpParams, x: BigInt): Boolean = SoftFloat.decode(p, x) match {
    case Decoded.Zero(_)           => true
    case Decoded.Finite(s, _, _)   => s
    case Decoded.Inf(s)            => s
    case Decoded.NaN(_)            => false
  }

  /** The Robust method's scale exponent: the exponent E of the largest |component|
    * (|x| in [2^E, 2^(E+1))), or 0 when every component is zero or any is infinite or NaN
    * (then scaling cannot help and the specials propagate unscaled).
    */
  def scaleExponent(p: FpParams, xs: Seq[BigInt]): Int = {
    val ds = xs.map(SoftFloat.decode(p, _))
    if (ds.exists { case Decoded.NaN(_) | Decoded.Inf(_) => true; case _ => false }) 0
    else {
      val es = ds.collect { case fin: Decoded.Finite => fin.topExp }
      if (es.isEmpty) 0 else es.max
    }
  }

  /** x * 2^e, rounded as the format's one rounder rounds (exact unless the result leaves the
    * normal range). Zeros and infinities keep their sign; NaN gives the canonical NaN (NV for
    * a signaling NaN). The RTL twin is Pow2Scale.
    */
  def pow2Scale(p: FpParams, x: BigInt, e: Int, rm: RoundingMode): FpResult = SoftFloat.decode(p, x) match {
    case Decoded.NaN(s)                 => SoftFloat.nan(p, if (s) FpFlags.Invalid else 0)
    case Decoded.Inf(s)                 => FpResult(p.format.infinity(s), 0)
    case Decoded.Zero(s)                => FpResult(p.format.zero(s), 0)
    case Decoded.Finite(s, sig, exp)    => SoftFloat.roundPack(p, s, sig, exp + e, sticky = false, rm)
  }

  /** A double rounded to format `f` (RNE, subnormals kept): how a host would store it. */
  def fromDouble(f: FloatFormat, v: Double): BigInt = {
    val fp64 = FpParams(FloatFormat.fp64)
    val bits = BigInt(java.lang.Double.doubleToRawLongBits(v)) & ((BigInt(1) << 64) - 1)
    if (f == FloatFormat.fp64) bits else FpConvertModel(fp64, FpParams(f), bits, RoundingMode.RNE).bits
  }

  /** The exact value of a format-`f` bit pattern as a double (every preset format fits). */
  def toDouble(f: FloatFormat, bits: BigInt): Double = {
    val fp64 = FpParams(FloatFormat.fp64)
    val b = if (f == FloatFormat.fp64) bits else FpConvertModel(FpParams(f), fp64, bits, RoundingMode.RNE).bits
    java.lang.Double.longBitsToDouble(b.toLong)
  }
}
