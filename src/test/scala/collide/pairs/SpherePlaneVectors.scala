package collide.pairs

import scala.util.Random
import collide.pairs.model.SpherePlanePair
import collide.scpu.ScpuConfig

/** Stimulus for the sphere/plane unit and its vectors file: hard cases by name, and random
  * pairs drawn as a scene would hold them (unit normals, as ODE keeps a plane) or as raw bit
  * patterns of the format (every special value and scale). */
final class SpherePlaneVectors(cfg: ScpuConfig) extends PairStimulus(cfg) {
  def pair(c: (Double, Double, Double), r: Double, n: (Double, Double, Double), d: Double): SpherePlanePair =
    SpherePlanePair(b(c._1), b(c._2), b(c._3), b(r), b(n._1), b(n._2), b(n._3), b(d))
  private val s = 1 / math.sqrt(3.0)

  /** Named hard cases (docs/pair-kinds.md lists them). */
  val hardCases: Seq[(String, SpherePlanePair)] = Seq(
    "resting on the floor, touching (depth exactly 0)" -> pair((0, 0, 1), 1, (0, 0, 1), 0),
    "sunk into the floor by half its radius" -> pair((0.25, -3, 0.5), 1, (0, 0, 1), 0),
    "the plane through the centre (depth = r)" -> pair((2, 3, 0), 0.75, (0, 0, 1), 0),
    "centre below the plane (depth > r)" -> pair((0, 0, -5), 1, (0, 0, 1), 0),
    "a ulp above touching (no contact)" -> pair((0, 0, 1.0 + math.ulp(1.0f).toDouble), 1, (0, 0, 1), 0),
    "a wall facing -x" -> pair((9.5, 0, 0), 1, (-1, 0, 0), -10),
    "an oblique plane" -> pair((1, 1, 1), 1, (s, s, s), 1),
    "an oblique plane, far side" -> pair((10, 10, 10), 1, (s, s, s), 1),
    "zero radius on the plane" -> pair((3, 4, 0), 0, (0, 0, 1), 0),
    "negative radius" -> pair((0, 0, 0.5), -1, (0, 0, 1), 0),
    "negative zero radius, centre on the plane" -> pair((0, 0, 0), -0.0, (0, 0, 1), 0),
    "a plane offset far from the origin" -> pair((0, 0, 1e4 - 0.5), 1, (0, 0, 1), 1e4),
    "very large scale" -> pair((3e30, 0, 1e30), 2e30, (0, 0, 1), 0),
    "very small scale" -> pair((0, 0, 1e-30), 2e-30, (0, 0, 1), 0),
    "a product that overflows the format" -> pair((biggest, biggest, 0), 1, (s, s, 0), 0),
    "a depth that overflows the format" -> pair((0, 0, -biggest), biggest, (0, 0, 1), 0),
    "a NaN coordinate" -> pair((Double.NaN, 0, 0), 1, (0, 0, 1), 0),
    "an infinite radius" -> pair((0, 0, 5), Double.PositiveInfinity, (0, 0, 1), 0),
    "an infinite offset" -> pair((0, 0, 5), 1, (0, 0, 1), Double.NegativeInfinity)
  )

  /** A sphere near a unit-normal plane in a box of `scale`: centre, radius, and the plane's
    * offset chosen so the depth spreads around zero (a third of them within a few ulps). */
  def random(rng: Random, scale: Double = 10): SpherePlanePair = {
    val n = unit(rng)
    val c = (rng.nextDouble() * 2 - 1, rng.nextDouble() * 2 - 1, rng.nextDouble() * 2 - 1)
    val cs = (c._1 * scale, c._2 * scale, c._3 * scale)
    val r = rng.nextDouble() * scale / 4
    val k = cs._1 * n._1 + cs._2 * n._2 + cs._3 * n._3
    val gap = rng.nextInt(3) match {
      case 0 => (rng.nextDouble() * 2 - 1) * r   // around the sphere's size
      case 1 => (rng.nextDouble() * 2 - 1) * r * 1e-6 // grazing
      case _ => 0.0                              // touching, up to rounding
    }
    pair(cs, r, n, k - r + gap)
  }
  /** Raw bit patterns of the format, every field: specials, subnormals, every scale. */
  def raw(rng: Random): SpherePlanePair = {
    def any(): BigInt = BigInt(f.width, rng)
    SpherePlanePair(any(), any(), any(), any(), any(), any(), any(), any())
  }
}
