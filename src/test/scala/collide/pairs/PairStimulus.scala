package collide.pairs

import scala.util.Random
import collide.fp.FloatFormat
import collide.scpu.ScpuConfig
import collide.scpu.model.ScpuModel

/** What the pair kinds' stimulus (SpherePlaneVectors, CapsuleSphereVectors) shares: values of
  * the configuration's format, its largest finite value, and random unit vectors. */
abstract class PairStimulus(cfg: ScpuConfig) {
  protected val f: FloatFormat = cfg.format
  /** A double rounded to the format (RNE), as its bit pattern. */
  def b(v: Double): BigInt = ScpuModel.fromDouble(f, v)
  protected val biggest: Double = ScpuModel.toDouble(f, f.maxFinite(false))
  /** A unit vector in a uniformly random direction. */
  protected def unit(rng: Random): (Double, Double, Double) = {
    val v = Seq.fill(3)(rng.nextGaussian())
    val l = math.sqrt(v.map(x => x * x).sum)
    (v(0) / l, v(1) / l, v(2) / l)
  }
}
