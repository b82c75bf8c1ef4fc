package collide.testutil

import java.math.{MathContext, RoundingMode => JRM, BigDecimal => JBigDecimal}
import collide.fp.{FloatFormat, FpFlags, RoundingMode}

/** Independent reference arithmetic for floating-point specs. Nothing here calls the golden
  * model (SoftFloat): operands are decoded by their own code, exact values live in
  * java.math.BigDecimal (MathContext.UNLIMITED) and rounding to a format uses
  * BigDecimal.setScale with Java's rounding modes, so a shared bug cannot hide.
  */
object FpOracle {
  sealed trait Value
  final case class NaN(signaling: Boolean) extends Value
  final case class Inf(negative: Boolean) extends Value
  /** A finite value; `negative` keeps the sign of zeros. */
  final case class Num(negative: Boolean, x: JBigDecimal) extends Value {
    def signed: JBigDecimal = if (negative) x.negate() else x
    def isZero: Boolean = x.signum == 0
  }

  val U = MathContext.UNLIMITED

  /** 2^k exactly. */
  def pow2(k: Int): JBigDecimal =
    if (k >= 0) new JBigDecimal(java.math.BigInteger.ONE.shiftLeft(k))
    else new JBigDecimal(java.math.BigInteger.valueOf(5).pow(-k), -k)

  /** Decodes a bit pattern; `daz` reads subnormals as zero. */
  def decode(f: FloatFormat, bits: BigInt, daz: Boolean = false): Value = {
    val neg  = bits.testBit(f.width - 1)
    val e    = ((bits >> (f.sigBits - 1)) & ((BigInt(1) << f.expBits) - 1)).toInt
    val frac = bits & ((BigInt(1) << (f.sigBits - 1)) - 1)
    val emax = (1 << f.expBits) - 1
    val bias = (1 << (f.expBits - 1)) - 1
    if (e == emax) { if (frac == 0) Inf(neg) else NaN(!frac.testBit(f.sigBits - 2)) }
    else if (e == 0) {
      if (daz) Num(neg, JBigDecimal.ZERO)
      else Num(neg, new JBigDecimal(frac.bigInteger).multiply(pow2(1 - bias - (f.sigBits - 1)), U))
    } else Num(neg, new JBigDecimal((frac + (BigInt(1) << (f.sigBits - 1))).bigInteger).multiply(pow2(e - bias - (f.sigBits - 1)), U))
  }

  /** floor(log2 |x|), x != 0. */
  def ilog2(x: JBigDecimal): Int = {
    val a = x.abs()
    var e = (a.unscaledValue.bitLength - 1 - math.floor(a.scale * (math.log(10) / math.log(2)))).toInt
    while (pow2(e).compareTo(a) > 0) e -= 1
    while (pow2(e + 1).compareTo(a) <= 0) e += 1
    e
  }

  private def jrm(rm: RoundingMode): JRM = rm match {
    case RoundingMode.RNE => JRM.HALF_EVEN
    case RoundingMode.RTZ => JRM.DOWN
    case RoundingMode.RDN => JRM.FLOOR
    case RoundingMode.RUP => JRM.CEILING
    case RoundingMode.RMM => JRM.HALF_UP
  }

  /** Rounds the exact signed value x (non-zero, or zero with the sign `negZero`) to `f`:
    * (bits, flags). Tininess before rounding; with `ftz`, tiny results flush to zero with
    * UF|NX. */
  def round(f: FloatFormat, x: JBigDecimal, rm: RoundingMode, ftz: Boolean = false, negZero: Boolean = false): (BigInt, Int) = {
    val bias  = (1 << (f.expBits - 1)) - 1
    val fracB = f.sigBits - 1
    val signB = BigInt(1) << (f.width - 1)
    if (x.signum == 0) return (if (negZero) signB else BigInt(0), 0)
    val neg  = x.signum < 0
    val sbit = if (neg) signB else BigInt(0)
    val e    = ilog2(x)
    val tiny = e < 1 - bias
    if (tiny && ftz) return (sbit, FpFlags.Underflow | FpFlags.Inexact)
    val q = math.max(e - fracB, 1 - bias - fracB) // exponent of the last place
    val scaled = x.multiply(pow2(-q), U)
    val n = scaled.setScale(0, jrm(rm))
    val inexact = n.compareTo(scaled) != 0
    val mag = BigInt(n.toBigIntegerExact.abs)
    val nx = if (inexact) FpFlags.Inexact else 0
    // Overflow: rounded magnitude (unbounded exponent) at or above 2^(emax+1).
    if (new JBigDecimal(mag.bigInteger).multiply(pow2(q), U).compareTo(pow2(bias + 1)) >= 0) {
      val toInf = rm match {
        case RoundingMode.RNE | RoundingMode.RMM => true
        case RoundingMode.RTZ => false
        case RoundingMode.RDN => neg
        case RoundingMode.RUP => !neg
      }
      val maxF = (BigInt((1 << f.expBits) - 2) << fracB) | ((BigInt(1) << fracB) - 1)
      val infB = BigInt((1 << f.expBits) - 1) << fracB
      return (sbit | (if (toInf) infB else maxF), FpFlags.Overflow | FpFlags.Inexact)
    }
    val uf = if (tiny && inexact) FpFlags.Underflow else 0
    val (m, qq) = if (mag.bitLength > f.sigBits) (mag >> 1, q + 1) else (mag, q)
    val bits =
      if (m.bitLength == f.sigBits) sbit | (BigInt(qq + fracB + bias) << fracB) | (m & ((BigInt(1) << fracB) - 1))
      else sbit | m // subnormal or zero
    (bits, nx | uf)
  }

  /** Rounds a Value (NaN -> canonical NaN, infinities kept) to `f`. */
  def roundValue(f: FloatFormat, v: Value, rm: RoundingMode, ftz: Boolean = false): (BigInt, Int) = v match {
    case NaN(_)   => (f.canonicalNaN, 0)
    case Inf(neg) => ((if (neg) BigInt(1) << (f.width - 1) else BigInt(0)) | (BigInt((1 << f.expBits) - 1) << (f.sigBits - 1)), 0)
    case n: Num   => round(f, n.signed, rm, ftz, negZero = n.negative)
  }

  // ---- JVM float/double bridges (exact both ways for formats they hold) ----

  def toDouble(f: FloatFormat, bits: BigInt): Double = decode(f, bits) match {
    case NaN(_)   => Double.NaN
    case Inf(neg) => if (neg) Double.NegativeInfinity else Double.PositiveInfinity
    case n: Num   => if (n.isZero) (if (n.negative) -0.0 else 0.0) else n.signed.doubleValue
  }
  def toFloat(f: FloatFormat, bits: BigInt): Float = toDouble(f, bits).toFloat // exact for formats within float

  def fromDouble(f: FloatFormat, d: Double, rm: RoundingMode = RoundingMode.RNE): BigInt =
    if (d.isNaN) f.canonicalNaN
    else if (d.isInfinite) roundValue(f, Inf(d < 0), rm)._1
    else round(f, new JBigDecimal(d), rm, negZero = (1.0 / d) < 0)._1

  /** Whether a result pattern is a NaN of `f` (JVM NaNs are compared by NaN-ness). */
  def isNaN(f: FloatFormat, bits: BigInt): Boolean = decode(f, bits).isInstanceOf[NaN]
}
