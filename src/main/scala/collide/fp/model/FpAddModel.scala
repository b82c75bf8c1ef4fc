package collide.fp.model

import collide.fp._

/** Golden a + b (a - b when `subtract`): the exact sum in BigInt, rounded by roundPack. */
object FpAddModel {
  import Decoded._

  def apply(p: FpParams, a: BigInt, b: BigInt, rm: RoundingMode, subtract: Boolean = false): FpResult = {
    val da = SoftFloat.decode(p, a)
    val db = SoftFloat.decode(p, b) match {
      case Inf(s)          => Inf(s ^ subtract)
      case Zero(s)         => Zero(s ^ subtract)
      case Finite(s, m, e) => Finite(s ^ subtract, m, e)
      case n               => n
    }
    val f = p.format
    val exactZeroSign = rm == RoundingMode.RDN // x + (-x) is +0, or -0 when rounding down
    (da, db) match {
      case (NaN(_), _) | (_, NaN(_)) => SoftFloat.nan(p, SoftFloat.snanFlags(p, a, b))
      case (Inf(sa), Inf(sb)) =>
        if (sa != sb) SoftFloat.nan(p, FpFlags.Invalid) else FpResult(f.infinity(sa), 0)
      case (Inf(s), _) => FpResult(f.infinity(s), 0)
      case (_, Inf(s)) => FpResult(f.infinity(s), 0)
      case (Zero(sa), Zero(sb)) => FpResult(f.zero(if (sa == sb) sa else exactZeroSign), 0)
      case _ =>
        def parts(d: Decoded): (BigInt, Int) = d match {
          case Finite(s, m, e) => (if (s) -m else m, e)
          case _               => (BigInt(0), Int.MaxValue)
        }
        val (ma, ea) = parts(da)
        val (mb, eb) = parts(db)
        val e   = math.min(ea, eb)
        val sum = (if (ma == 0) BigInt(0) else ma << (ea - e)) + (if (mb == 0) BigInt(0) else mb << (eb - e))
        if (sum == 0) FpResult(f.zero(exactZeroSign), 0)
        else SoftFloat.roundPack(p, sum < 0, sum.abs, e, sticky = false, rm)
    }
  }
}
