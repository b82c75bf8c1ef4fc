package collide.scpu.model

import collide.scpu.ContactKind

/** A 3-vector of doubles (reports and the reference only). */
final case class V3(x: Double, y: Double, z: Double) {
  def toSeq: Seq[Double] = Seq(x, y, z)
}

/** A contact in double precision. Fields other than hit/kind are 0 when there is no hit. */
final case class OdeContact(hit: Boolean, kind: Int, pos: V3, normal: V3, depth: Double)

/** ODE's dCollideSpheres in IEEE double, operation for operation in ODE's order (ODE 0.16,
  * ode/src/collision_util.cpp; dCalcPointsDistance3 sums dx*dx + dy*dy + dz*dz left to right;
  * r2 - r1 - d and r1 + r2 - d associate to the left). The accuracy reference for every
  * preset: the report feeds it the compute-format inputs (exact in double) and measures the SCPU's outputs
  * against it. One deliberate difference from ODE: ODE tests `d > r1 + r2`, so a NaN distance
  * falls through to a contact; here (as in the SCPU) a NaN distance is no contact.
  */
object OdeReference {
  def collide(p1: V3, r1: Double, p2: V3, r2: Double): OdeContact = {
    val dx = p1.x - p2.x
    val dy = p1.y - p2.y
    val dz = p1.z - p2.z
    val d  = math.sqrt(dx * dx + dy * dy + dz * dz)
    if (!(d <= r1 + r2)) OdeContact(hit = false, ContactKind.Separated, V3(0, 0, 0), V3(0, 0, 0), 0.0)
    else if (d <= 0) OdeContact(hit = true, ContactKind.Coincident, p1, V3(1, 0, 0), r1 + r2)
    else {
      val inv = 1.0 / d
      val n   = V3(dx * inv, dy * inv, dz * inv)
      val k   = 0.5 * (r2 - r1 - d)
      OdeContact(hit = true, ContactKind.Contact, V3(p1.x + n.x * k, p1.y + n.y * k, p1.z + n.z * k), n, r1 + r2 - d)
    }
  }
}
