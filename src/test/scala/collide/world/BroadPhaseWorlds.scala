package collide.world

import scala.util.Random
import collide.fp.FloatFormat
import collide.scpu.model.ScpuModel
import collide.world.model.WorldSphere

/** Worlds for the broad-phase specs, in doubles (converted to the link format by `bits`):
  * the random clouds and the hard cases of docs/afu.md's world-mode section. */
object BroadPhaseWorlds {
  final case class S(x: Double, y: Double, z: Double, r: Double)

  def bits(f: FloatFormat, w: Seq[S]): IndexedSeq[WorldSphere] = w.map { s =>
    WorldSphere(ScpuModel.fromDouble(f, s.x), ScpuModel.fromDouble(f, s.y), ScpuModel.fromDouble(f, s.z),
      ScpuModel.fromDouble(f, s.r))
  }.toIndexedSeq

  /** n spheres of radius r in a cube sized for about `contacts` neighbours within 2r each. */
  def uniform(rng: Random, n: Int, r: Double = 0.5, contacts: Double = 2.0, origin: Double = 0.0): Seq[S] = {
    val side = math.cbrt(n * (4.0 / 3) * math.Pi * math.pow(2 * r, 3) / contacts)
    Seq.fill(n)(S(origin + rng.nextDouble() * side, origin + rng.nextDouble() * side,
      origin + rng.nextDouble() * side, r))
  }

  def clustered(rng: Random, n: Int, clusters: Int = 4): Seq[S] = {
    val centres = Seq.fill(clusters)((rng.nextDouble() * 20 - 10, rng.nextDouble() * 20 - 10, rng.nextDouble() * 20 - 10))
    Seq.tabulate(n) { i =>
      val (cx, cy, cz) = centres(i % clusters)
      S(cx + rng.nextGaussian(), cy + rng.nextGaussian(), cz + rng.nextGaussian(), 0.3 + 0.2 * rng.nextDouble())
    }
  }

  /** Radii log-uniform over 1:1000. */
  def mixedRadii(rng: Random, n: Int): Seq[S] =
    Seq.fill(n)(S(rng.nextDouble() * 30 - 15, rng.nextDouble() * 30 - 15, rng.nextDouble() * 30 - 15,
      0.01 * math.pow(1000, rng.nextDouble())))

  /** Small spheres plus a few huge ones spanning many cells, radii 20, 80, 320, ... */
  def huge(rng: Random, n: Int, big: Int): Seq[S] =
    uniform(rng, n) ++ Seq.tabulate(big)(i => S(rng.nextDouble() * 8, rng.nextDouble() * 8, rng.nextDouble() * 8, 20.0 * math.pow(4, i)))

  /** Zero radii and separations whose squares underflow: hits decided by underflow. */
  val tinySeparations: Seq[S] = Seq(S(0, 0, 0, 0), S(1e-20, 0, 0, 0), S(3e-20, 0, 0, 1e-20), S(0, 1e-39, 0, 0),
    S(0, 0, 0, 0), S(-1e-20, 0, 0, 2e-20), S(5e-30, 5e-30, 0, 0),
    // squares that underflow to zero: binary32 (1e-24) and fp16 (1e-4) call these hits
    S(1e-24, 0, 0, 0), S(0, -3e-24, 0, 0), S(1e-4, 0, 0, 0), S(0, 0, -2e-4, 0), S(-1e-4, 1e-4, 0, 0))

  def onePoint(n: Int): Seq[S] = Seq.tabulate(n)(i => S(1.5, -2.25, 3.0, 0.25 + 0.25 * (i % 3)))

  /** Radius 0.375 makes the cell edge 1 (0.84375 -> 1): a lattice of touching spheres (spacing 0.75) crossing
    * every cell face, plus spheres exactly on and one ulp either side of integer faces. */
  def cellBoundaries(rng: Random): Seq[S] = facesOf(rng, edge = 1.0, r = 0.375)

  /** The same on the faces of cells of edge 1.5 (radius 0.5 needs 1.125: such cells with two
    * cell steps an octave, edge 2 with one): x at multiples of 1.5 and one ulp either side. */
  def oneAndAHalfBoundaries(rng: Random): Seq[S] = facesOf(rng, edge = 1.5, r = 0.5)

  private def facesOf(rng: Random, edge: Double, r: Double): Seq[S] = {
    val h = 0.75 * edge
    val lattice = for (i <- -3 to 3; j <- -2 to 2) yield S(h * i, h * j, 0.0, r)
    val faces = Seq.tabulate(40) { _ =>
      val m = (rng.nextInt(7) - 3) * edge
      val x = rng.nextInt(3) match { case 0 => m; case 1 => math.nextUp(m); case _ => math.nextDown(m) }
      S(x, (rng.nextInt(3) - 1.0) * edge + h * rng.nextInt(2), rng.nextDouble() * 2 - 1, r)
    }
    lattice ++ faces
  }

  /** Pairs at (r1 + r2)(1 + e) apart for tiny e of both signs, each straddling a cell face:
    * the pairs whose hit decision is a matter of rounding. */
  def nearMisses(rng: Random, pairs: Int, ulp: Double): Seq[S] = Seq.fill(pairs) {
    val r1 = 0.2 + 0.3 * rng.nextDouble(); val r2 = 0.2 + 0.3 * rng.nextDouble()
    val (ux, uy, uz) = { val v = Seq.fill(3)(rng.nextGaussian()); val l = math.sqrt(v.map(a => a * a).sum); (v(0) / l, v(1) / l, v(2) / l) }
    val d = (r1 + r2) * (1 + ulp * (rng.nextInt(17) - 8))
    val x = (rng.nextInt(9) - 4).toDouble - ux * d / 2; val y = rng.nextDouble() * 4 - 2; val z = rng.nextDouble() * 4 - 2
    Seq(S(x, y, z, r1), S(x + ux * d, y + uy * d, z + uz * d, r2))
  }.flatten

  /** The hard cases of docs/afu.md's world-mode section and random clouds, small enough for
    * every-pair checks: what the model's spec and the RTL's spec both run. */
  def hardCases(rng: Random, onePointSpheres: Int): Seq[(String, Seq[S])] = Seq(
    "an empty world" -> Seq.empty,
    "one sphere" -> Seq(S(1, 2, 3, 0.5)),
    "a uniform cloud" -> uniform(rng, 120),
    "a clustered cloud" -> clustered(rng, 100),
    "radii over 1:1000" -> mixedRadii(rng, 90),
    "huge spheres among small ones" -> huge(rng, 80, 3),
    "all spheres at one point" -> onePoint(onePointSpheres),
    "zero radii and underflowing separations" -> tinySeparations,
    "spheres on cell faces" -> cellBoundaries(rng),
    "spheres on faces of 1.5-wide cells" -> oneAndAHalfBoundaries(rng),
    "negative coordinates" -> uniform(rng, 80, origin = -1000.0),
    "near misses across cell faces" -> nearMisses(rng, 40, math.pow(2, -10))
  )
}
