package collide.fp.model

import collide.fp._

/** Golden conversion between formats: decode exactly in `from` (DAZ if from flushes), round
  * to `to` with roundPack (FTZ if to flushes). Every NaN becomes `to`'s canonical NaN. */
object FpConvertModel {
  import Decoded._

  def apply(from: FpParams, to: FpParams, a: BigInt, rm: RoundingMode): FpResult = {
    val tf = to.format
    SoftFloat.decode(from, a) match {
      case NaN(s)          => SoftFloat.nan(to, if (s) FpFlags.Invalid else 0)
      case Inf(s)          => FpResult(tf.infinity(s), 0)
      case Zero(s)         => FpResult(tf.zero(s), 0)
      case Finite(s, m, e) => SoftFloat.roundPack(to, s, m, e, sticky = false, rm)
    }
  }
}
