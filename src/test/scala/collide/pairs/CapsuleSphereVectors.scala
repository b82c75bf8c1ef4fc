package collide.pairs

import scala.util.Random
import collide.pairs.model.CapsuleSpherePair
import collide.scpu.ScpuConfig

/** Stimulus for the capsule/sphere unit and its vectors file: hard cases by name, random
  * capsules with spheres about them (a third grazing), and raw bit patterns of the format. */
final class CapsuleSphereVectors(cfg: ScpuConfig) extends PairStimulus(cfg) {
  def pair(c: (Double, Double, Double), a: (Double, Double, Double), lz: Double, rc: Double,
           s: (Double, Double, Double), rs: Double): CapsuleSpherePair =
    CapsuleSpherePair(b(c._1), b(c._2), b(c._3), b(a._1), b(a._2), b(a._3), b(lz), b(rc), b(s._1), b(s._2), b(s._3), b(rs))
  private val z = (0.0, 0.0, 1.0)
  private val o = (0.0, 0.0, 0.0)
  private val k = 1 / math.sqrt(3.0)

  /** Named hard cases (docs/pair-kinds.md lists them). */
  val hardCases: Seq[(String, CapsuleSpherePair)] = Seq(
    "beside the middle, sunk" -> pair(o, z, 2, 1, (1.5, 0, 0), 1),
    "touching the side exactly" -> pair(o, z, 2, 1, (2, 0, 0), 1),
    "touching the +z cap exactly (alpha clamped to lz/2)" -> pair(o, z, 2, 1, (0, 0, 3), 1),
    "beyond the -z cap, sunk (alpha clamped to -lz/2)" -> pair(o, z, 2, 1, (0.5, 0, -2.5), 1),
    "past the end, separated" -> pair(o, z, 2, 1, (0, 0, 3.5), 1),
    "the sphere's centre on the axis (coincident)" -> pair(o, z, 2, 1, (0, 0, 0.5), 0.25),
    "the sphere's centre at the capsule's centre" -> pair((1, 2, 3), z, 2, 1, (1, 2, 3), 0.5),
    "a zero-length capsule (a sphere)" -> pair(o, (1, 0, 0), 0, 1, (1.5, 0.5, 0), 1),
    "an oblique axis" -> pair((1, 1, 1), (k, k, k), 4, 0.5, (2, 1, 1), 0.75),
    "an axis along -y" -> pair(o, (0, -1, 0), 10, 0.1, (0.15, -4.9, 0), 0.1),
    "a negative length" -> pair(o, z, -2, 1, (0, 0, 1.5), 1),
    "very large scale" -> pair((1e30, 0, 0), z, 4e30, 1e30, (2.5e30, 0, 1e30), 1e30),
    "very small scale" -> pair(o, z, 4e-30, 1e-30, (1.5e-30, 0, 1e-30), 1e-30),
    "a product that overflows the format" -> pair((-biggest, 0, 0), (1, 0, 0), 1, 1, (biggest, 0, 0), 1),
    "a NaN axis" -> pair(o, (Double.NaN, 0, 0), 2, 1, (1, 0, 0), 1),
    "an infinite length" -> pair(o, z, Double.PositiveInfinity, 1, (1, 0, 1e3), 1),
    "an infinite sphere centre" -> pair(o, z, 2, 1, (Double.NegativeInfinity, 0, 0), 1)
  )

  /** A capsule in a box of `scale`, and a sphere at a random place along its axis (ends and
    * beyond included), off the axis by about the sum of the radii (a third within 1e-6 of it). */
  def random(rng: Random, scale: Double = 10): CapsuleSpherePair = {
    val a = unit(rng)
    val c = (rng.nextDouble() * 2 - 1, rng.nextDouble() * 2 - 1, rng.nextDouble() * 2 - 1)
    val cs = (c._1 * scale, c._2 * scale, c._3 * scale)
    val lz = rng.nextDouble() * scale
    val rc = rng.nextDouble() * scale / 8
    val rs = rng.nextDouble() * scale / 8
    val t = (rng.nextDouble() * 1.6 - 0.8) * lz
    // A direction off the axis: a random unit vector minus its part along the axis.
    val u = unit(rng)
    val ua = u._1 * a._1 + u._2 * a._2 + u._3 * a._3
    val perp0 = (u._1 - ua * a._1, u._2 - ua * a._2, u._3 - ua * a._3)
    val pl = math.sqrt(perp0._1 * perp0._1 + perp0._2 * perp0._2 + perp0._3 * perp0._3)
    val perp = (perp0._1 / pl, perp0._2 / pl, perp0._3 / pl)
    val off = (rc + rs) * (rng.nextInt(3) match {
      case 0 => 0.5 + rng.nextDouble()
      case 1 => 1 + (rng.nextDouble() * 2 - 1) * 1e-6
      case _ => rng.nextDouble()
    })
    val s = (cs._1 + t * a._1 + off * perp._1, cs._2 + t * a._2 + off * perp._2, cs._3 + t * a._3 + off * perp._3)
    pair(cs, a, lz, rc, s, rs)
  }
  /** Raw bit patterns of the format, every field. */
  def raw(rng: Random): CapsuleSpherePair = {
    def any(): BigInt = BigInt(f.width, rng)
    CapsuleSpherePair(any(), any(), any(), any(), any(), any(), any(), any(), any(), any(), any(), any())
  }
}
