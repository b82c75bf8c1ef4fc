package collide.fp.model

import collide.fp._

/** A quiet comparison's outcome (exactly one of lt, eq, gt, unordered) with its flags, and
  * minimumNumber / maximumNumber as bit patterns (see FpCompareOut). */
final case class CompareResult(lt: Boolean, eq: Boolean, gt: Boolean, unordered: Boolean, flags: Int,
                               min: BigInt = 0, max: BigInt = 0) {
  def show: String =
    Seq(lt -> "lt", eq -> "eq", gt -> "gt", unordered -> "unordered").collect { case (true, n) => n }.mkString("|") +
      s" [${FpFlags.show(flags)}] min=0x${min.toString(16)} max=0x${max.toString(16)}"
}

/** Golden quiet comparison: NV only for signaling NaNs, -0 == +0, DAZ when p.subnormals is
  * false. Values are compared exactly (as sign, significand, exponent). */
object FpCompareModel {
  import Decoded._

  /** -1, 0, 1 for x < y, x == y, x > y; NaNs excluded by the caller. min/max order -0 < +0
    * when `signedZeros`. */
  private def order(x: Decoded, y: Decoded, signedZeros: Boolean): Int = {
    // Key: (class, magnitude) with class -2 -inf, -1 negative finite, 0 zero, 1 positive, 2 +inf.
    def cls(d: Decoded): Int = d match {
      case Inf(s)          => if (s) -2 else 2
      case Finite(s, _, _) => if (s) -1 else 1
      case _               => 0
    }
    (x, y) match {
      case (Zero(sx), Zero(sy)) => if (signedZeros && sx != sy) (if (sx) -1 else 1) else 0
      case (Finite(s, mx, ex), Finite(s2, my, ey)) if s == s2 =>
        val e = math.min(ex, ey)
        val c = (mx << (ex - e)).compare(my << (ey - e))
        if (s) -c else c
      case _ => Integer.compare(cls(x), cls(y))
    }
  }

  def apply(p: FpParams, a: BigInt, b: BigInt): CompareResult = {
    val f  = p.format
    val da = SoftFloat.decode(p, a)
    val db = SoftFloat.decode(p, b)
    val flags = SoftFloat.snanFlags(p, a, b)
    // The bits min/max return: the operand, or the zero it reads as under DAZ.
    def asRead(bits: BigInt, d: Decoded): BigInt = d match {
      case Zero(s) => f.zero(s)
      case _       => bits
    }
    (da, db) match {
      case (NaN(_), NaN(_)) => CompareResult(false, false, false, true, flags, f.canonicalNaN, f.canonicalNaN)
      case (NaN(_), _)      => CompareResult(false, false, false, true, flags, asRead(b, db), asRead(b, db))
      case (_, NaN(_))      => CompareResult(false, false, false, true, flags, asRead(a, da), asRead(a, da))
      case _ =>
        val c  = order(da, db, signedZeros = false)
        val cz = order(da, db, signedZeros = true)
        val (mn, mx) = if (cz < 0) (asRead(a, da), asRead(b, db)) else (asRead(b, db), asRead(a, da))
        CompareResult(c < 0, c == 0, c > 0, false, flags, mn, mx)
    }
  }
}
