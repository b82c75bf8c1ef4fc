package collide.pairs.model

import collide.fp._
import collide.fp.model._
import collide.scpu.ScpuConfig

/** One sphere and one plane in a compute format: the sphere's centre and radius, and the plane
  * as ODE keeps it (dGeomPlaneGetParams: a unit normal n and an offset d, the plane being
  * n . x = d). Bit patterns of the format. */
final case class SpherePlanePair(cx: BigInt, cy: BigInt, cz: BigInt, r: BigInt,
                                 nx: BigInt, ny: BigInt, nz: BigInt, d: BigInt, tag: BigInt = 0) {
  def fields: Seq[BigInt] = Seq(cx, cy, cz, r, nx, ny, nz, d)
}

/** dCollideSpherePlane's one contact (zero fields when there is none): the deepest point of the
  * sphere, the plane's normal and the depth. `flags` ORs the flags of every operator on the path
  * that gave the result (the decision's always; the position's for a contact only). */
final case class SpherePlaneResult(hit: Boolean, px: BigInt, py: BigInt, pz: BigInt,
                                   nx: BigInt, ny: BigInt, nz: BigInt, depth: BigInt,
                                   nonFinite: Boolean, flags: Int, tag: BigInt) {
  def fields: Seq[BigInt] = Seq(px, py, pz, nx, ny, nz, depth)
}

/** Golden model of the SpherePlane unit, bit for bit: ODE 0.16's dCollideSpherePlane
  * (ode/src/sphere.cpp) operation for operation in the configuration's format and
  * rounding:
  * {{{
  *   k     = (cx nx + cy ny) + cz nz          dCalcVectorDot3, left to right
  *   depth = (d - k) + r                      plane->p[3] - k + sphere->radius
  *   hit   = depth >= 0                       (a NaN depth is no contact, as in ODE)
  *   pos   = c - n r,  normal = n
  * }}}
  * In binary64 with round-to-nearest-even this is ODE's own arithmetic (IEEE double, no fused
  * multiply-add), so its contacts equal dCollide's bit for bit (test/test_pair_kinds.cpp checks).
  */
final class SpherePlaneModel(val cfg: ScpuConfig) {
  private val p  = cfg.params
  private val rm = cfg.rm
  private def add(a: BigInt, b: BigInt) = FpAddModel(p, a, b, rm, subtract = false)
  private def sub(a: BigInt, b: BigInt) = FpAddModel(p, a, b, rm, subtract = true)
  private def mul(a: BigInt, b: BigInt) = FpMulModel(p, a, b, rm)

  /** depth >= 0 as a sign test: true for +0, -0 and every positive value, false for NaN. */
  def notNegative(x: BigInt): Boolean = SoftFloat.decode(p, x) match {
    case Decoded.NaN(_)         => false
    case Decoded.Zero(_)        => true
    case Decoded.Inf(s)         => !s
    case Decoded.Finite(s, _, _) => !s
  }

  def collide(in: SpherePlanePair): SpherePlaneResult = {
    val nonFinite = in.fields.exists(x => SoftFloat.decode(p, x) match {
      case Decoded.NaN(_) | Decoded.Inf(_) => true
      case _                               => false
    })
    val mx = mul(in.cx, in.nx); val my = mul(in.cy, in.ny); val mz = mul(in.cz, in.nz)
    val s = add(mx.bits, my.bits)
    val k = add(s.bits, mz.bits)
    val e = sub(in.d, k.bits)
    val depth = add(e.bits, in.r)
    val hit = notNegative(depth.bits)
    val baseFlags = Seq(mx, my, mz, s, k, e, depth).map(_.flags).reduce(_ | _)
    if (!hit) SpherePlaneResult(false, 0, 0, 0, 0, 0, 0, 0, nonFinite, baseFlags, in.tag)
    else {
      val nr = Seq(in.nx, in.ny, in.nz).map(n => mul(n, in.r))
      val pos = Seq(in.cx, in.cy, in.cz).zip(nr).map { case (c, t) => sub(c, t.bits) }
      val flags = baseFlags | (nr ++ pos).map(_.flags).reduce(_ | _)
      SpherePlaneResult(true, pos(0).bits, pos(1).bits, pos(2).bits, in.nx, in.ny, in.nz, depth.bits, nonFinite, flags, in.tag)
    }
  }
}
