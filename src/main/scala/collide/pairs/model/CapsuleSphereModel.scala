package collide.pairs.model

import collide.fp.model._
import collide.scpu.ScpuConfig
import collide.scpu.model.{ScpuModel, ScpuPair, ScpuResult}

/** A capsule and a sphere in a compute format: the capsule's centre, its axis (the third column
  * of its rotation, R[2], R[6], R[10]: a unit vector as ODE keeps it), its length lz (end to end
  * of the cylinder part, as dCreateCapsule takes it) and radius; the sphere's centre and radius. */
final case class CapsuleSpherePair(cx: BigInt, cy: BigInt, cz: BigInt, ax: BigInt, ay: BigInt, az: BigInt,
                                   lz: BigInt, rc: BigInt, sx: BigInt, sy: BigInt, sz: BigInt, rs: BigInt,
                                   tag: BigInt = 0) {
  def fields: Seq[BigInt] = Seq(cx, cy, cz, ax, ay, az, lz, rc, sx, sy, sz, rs)
}

/** Golden model of the CapsuleSphere unit, bit for bit: ODE 0.16's dCollideCapsuleSphere
  * (ode/src/capsule.cpp) in the configuration's format and rounding. The point of the axis
  * nearest the sphere, then ODE's dCollideSpheres on it (the SCPU's arithmetic, ScpuModel):
  * {{{
  *   alpha = (ax (sx - cx) + ay (sy - cy)) + az (sz - cz)
  *   lz2   = lz 0.5
  *   if (alpha > lz2) alpha = lz2;  if (alpha < -lz2) alpha = -lz2     (NaN stays NaN)
  *   p     = c + alpha a
  *   dCollideSpheres(p, rc, s, rs)
  * }}}
  * The result is the SCPU's (kind, pos, normal, depth, and d and w for a derived record), its
  * flags those of the segment stage ORed with the SCPU's, `nonFinite` over all twelve inputs.
  * Only for configurations whose SCPU takes the compute format itself (no link conversion).
  */
final class CapsuleSphereModel(val cfg: ScpuConfig) {
  require(!cfg.converts, s"CapsuleSphereModel: SCPU ${cfg.name} converts its link values; the capsule unit takes the compute format")
  private val p  = cfg.params
  private val rm = cfg.rm
  private val f  = cfg.format
  private val spheres = ScpuModel(cfg)
  private def add(a: BigInt, b: BigInt) = FpAddModel(p, a, b, rm, subtract = false)
  private def sub(a: BigInt, b: BigInt) = FpAddModel(p, a, b, rm, subtract = true)
  private def mul(a: BigInt, b: BigInt) = FpMulModel(p, a, b, rm)
  private val half: BigInt = BigInt(f.bias - 1) << f.fracBits

  /** The sphere SCPU's pair for this capsule and sphere (the axis point p with the capsule's
    * radius, then the sphere) and the segment stage's flags. */
  def segment(in: CapsuleSpherePair): (ScpuPair, Int) = {
    val c = Seq(in.cx, in.cy, in.cz)
    val a = Seq(in.ax, in.ay, in.az)
    val s = Seq(in.sx, in.sy, in.sz)
    val diff = s.zip(c).map { case (si, ci) => sub(si, ci) }
    val lz2 = mul(in.lz, half)
    val m = a.zip(diff).map { case (ai, di) => mul(ai, di.bits) }
    val a01 = add(m(0).bits, m(1).bits)
    val alpha = add(a01.bits, m(2).bits)
    val c1 = FpCompareModel(p, alpha.bits, lz2.bits)
    val clamp1 = if (c1.gt) lz2.bits else alpha.bits
    val negLz2 = lz2.bits ^ f.signBit
    val c2 = FpCompareModel(p, clamp1, negLz2)
    val clamped = if (c2.lt) negLz2 else clamp1
    val q = a.map(ai => mul(clamped, ai))
    val pt = c.zip(q).map { case (ci, qi) => add(ci, qi.bits) }
    val flags = (diff ++ m ++ q ++ pt :+ lz2 :+ a01 :+ alpha).map(_.flags).reduce(_ | _) | c1.flags | c2.flags
    (ScpuPair(pt(0).bits, pt(1).bits, pt(2).bits, in.rc, in.sx, in.sy, in.sz, in.rs, in.tag), flags)
  }

  def collide(in: CapsuleSpherePair): ScpuResult = {
    val (pair, segFlags) = segment(in)
    val nonFinite = in.fields.exists(x => SoftFloat.decode(p, x) match {
      case Decoded.NaN(_) | Decoded.Inf(_) => true
      case _                               => false
    })
    val r = spheres.collide(pair)
    r.copy(nonFinite = nonFinite, flags = r.flags | segFlags)
  }
}
