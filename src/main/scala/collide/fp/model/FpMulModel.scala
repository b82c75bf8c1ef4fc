package collide.fp.model

import collide.fp._

/** Golden a * b: the exact product in BigInt, rounded by roundPack. 0 * inf is invalid. */
object FpMulModel {
  import Decoded._

  def apply(p: FpParams, a: BigInt, b: BigInt, rm: RoundingMode): FpResult = {
    val f = p.format
    (SoftFloat.decode(p, a), SoftFloat.decode(p, b)) match {
      case (NaN(_), _) | (_, NaN(_))       => SoftFloat.nan(p, SoftFloat.snanFlags(p, a, b))
      case (Inf(_), Zero(_)) | (Zero(_), Inf(_)) => SoftFloat.nan(p, FpFlags.Invalid)
      case (x, y) if x.isInstanceOf[Inf] || y.isInstanceOf[Inf] => FpResult(f.infinity(x.sign ^ y.sign), 0)
      case (x, y) if x.isInstanceOf[Zero] || y.isInstanceOf[Zero] => FpResult(f.zero(x.sign ^ y.sign), 0)
      case (Finite(sa, ma, ea), Finite(sb, mb, eb)) =>
        SoftFloat.roundPack(p, sa ^ sb, ma * mb, ea + eb, sticky = false, rm)
      case other => throw new IllegalStateException(s"FpMulModel: unreachable $other")
    }
  }
}
