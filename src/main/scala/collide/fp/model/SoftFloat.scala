package collide.fp.model

import collide.fp._

/** Result of a golden-model operation: the bit pattern and the FpFlags raised. */
final case class FpResult(bits: BigInt, flags: Int) {
  def show(f: FloatFormat): String = s"0x${bits.toString(16)} [${FpFlags.show(flags)}]"
}

/** An operand decoded exactly. Finite non-zero values are (-1)^sign * sig * 2^exp, sig > 0. */
sealed trait Decoded { def sign: Boolean }
object Decoded {
  final case class NaN(signaling: Boolean) extends Decoded { val sign = false }
  final case class Inf(sign: Boolean) extends Decoded
  final case class Zero(sign: Boolean) extends Decoded
  final case class Finite(sign: Boolean, sig: BigInt, exp: Int) extends Decoded {
    require(sig > 0)
    /** Exponent of the most significant bit: value in [2^topExp, 2^(topExp+1)). */
    def topExp: Int = exp + sig.bitLength - 1
  }
}

/** The golden model's core: exact decoding and exact rounding. Every operator's model
  * computes its exact result (or enough bits plus a sticky flag) with BigInt and hands it
  * to [[roundPack]], so the models are bit-accurate by construction and the RTL, which
  * shares the rounding rules, is checked against them.
  *
  * Conventions (the RTL follows them too):
  *  - tininess is detected before rounding (exact |result| < 2^minExp);
  *  - underflow is raised when the result is tiny and inexact (IEEE default exception
  *    handling); with subnormals flushed, a tiny result becomes zero with UF|NX;
  *  - every NaN result is the format's canonical NaN; invalid is raised for signaling NaN
  *    operands and invalid operations.
  */
object SoftFloat {
  import Decoded._

  def decode(p: FpParams, bits: BigInt): Decoded = {
    val f = p.format
    require(bits >= 0 && bits.bitLength <= f.width, s"operand 0x${bits.toString(16)} does not fit ${f.name}")
    val sign = bits.testBit(f.width - 1)
    val e    = ((bits >> f.fracBits) & f.expMask).toInt
    val frac = bits & f.fracMask
    if (e == f.expMask.toInt) {
      if (frac == 0) Inf(sign) else NaN(signaling = !frac.testBit(f.fracBits - 1))
    } else if (e == 0) {
      if (frac == 0 || !p.subnormals) Zero(sign) else Finite(sign, frac, f.minSubExp)
    } else Finite(sign, frac | (BigInt(1) << f.fracBits), e - f.bias - f.fracBits)
  }

  def isSignalingNaN(p: FpParams, bits: BigInt): Boolean = decode(p, bits) match {
    case NaN(true) => true
    case _         => false
  }

  /** Encodes a value that is exactly representable (used by tests and conversions). */
  def encodeExact(p: FpParams, sign: Boolean, sig: BigInt, exp: Int): BigInt = {
    val r = roundPack(p, sign, sig, exp, sticky = false, RoundingMode.RNE)
    require(r.flags == 0, s"value $sig*2^$exp is not exact in ${p.name}")
    r.bits
  }

  /** Rounds (-1)^sign * (sig + s) * 2^exp to `p`, where s = 0 if !sticky and 0 < s < 1 if
    * sticky. When sticky is set, the caller must supply at least one bit below the result's
    * last place (sig * 2^exp carries a round bit), which every operator model guarantees.
    * A zero value (sig == 0, !sticky) returns a zero of the given sign with no flags.
    */
  def roundPack(p: FpParams, sign: Boolean, sig: BigInt, exp: Int, sticky: Boolean, rm: RoundingMode): FpResult = {
    require(sig >= 0)
    val f = p.format
    if (sig == 0 && !sticky) return FpResult(f.zero(sign), 0)
    // Replace "sig plus something in (0,1)" by sig + 1/2: the same rounding, because the
    // result's half-ulp points are multiples of 2^exp (checked below).
    val (s, e) = if (sticky) ((sig << 1) | 1, exp - 1) else (sig, exp)
    val top  = e + s.bitLength - 1
    val tiny = top < f.minExp
    if (tiny && !p.subnormals)
      return FpResult(f.zero(sign), FpFlags.Underflow | FpFlags.Inexact)
    val q     = math.max(top - f.fracBits, f.minSubExp) // exponent of the result's last place
    val shift = q - e
    if (sticky) require(shift >= 2, s"roundPack: sticky given without a round bit (shift $shift)")
    val (m0, rem, half) =
      if (shift <= 0) (s << -shift, BigInt(0), BigInt(1))
      else (s >> shift, s & ((BigInt(1) << shift) - 1), BigInt(1) << (shift - 1))
    val inexact = rem != 0
    val up = rm match {
      case RoundingMode.RNE => rem > half || (rem == half && shift > 0 && m0.testBit(0))
      case RoundingMode.RMM => shift > 0 && rem >= half
      case RoundingMode.RTZ => false
      case RoundingMode.RDN => inexact && sign
      case RoundingMode.RUP => inexact && !sign
    }
    var m  = m0 + (if (up) 1 else 0)
    var qq = q
    if (m.bitLength > f.sigBits) { m = m >> 1; qq += 1 } // carry out of rounding: m was 2^sigBits
    var flags = (if (inexact) FpFlags.Inexact else 0) | (if (tiny && inexact) FpFlags.Underflow else 0)
    if (qq + f.fracBits > f.maxExp) {
      flags = FpFlags.Overflow | FpFlags.Inexact
      val toInf = rm match {
        case RoundingMode.RNE | RoundingMode.RMM => true
        case RoundingMode.RTZ                    => false
        case RoundingMode.RDN                    => sign
        case RoundingMode.RUP                    => !sign
      }
      return FpResult(if (toInf) f.infinity(sign) else f.maxFinite(sign), flags)
    }
    val signBits = if (sign) f.signBit else BigInt(0)
    val bits =
      if (m.testBit(f.fracBits)) signBits | (BigInt(qq + f.fracBits + f.bias) << f.fracBits) | (m & f.fracMask)
      else signBits | m // subnormal or zero (qq == minSubExp here)
    FpResult(bits, flags)
  }

  /** Shorthand for models: the canonical NaN with the given flags. */
  def nan(p: FpParams, flags: Int): FpResult = FpResult(p.format.canonicalNaN, flags)

  /** Invalid flag if any operand is a signaling NaN (for quiet NaN propagation). */
  def snanFlags(p: FpParams, ops: BigInt*): Int =
    if (ops.exists(isSignalingNaN(p, _))) FpFlags.Invalid else 0

  /** sig * 2^exp as an exact BigDecimal. Scala's BigDecimal rounds to 34 digits by default:
    * everything here carries MathContext.UNLIMITED, and so must any oracle built on it. */
  def exactDecimal(sig: BigInt, exp: Int): BigDecimal =
    if (exp >= 0) BigDecimal(sig << exp, java.math.MathContext.UNLIMITED)
    else BigDecimal(sig * BigInt(5).pow(-exp), -exp, java.math.MathContext.UNLIMITED)

  /** The exact value of a finite operand as BigDecimal (for oracles and reports). */
  def toBigDecimal(p: FpParams, bits: BigInt): Option[BigDecimal] = decode(p, bits) match {
    case Zero(_)            => Some(BigDecimal(0))
    case Finite(s, sig, e)  => Some(exactDecimal(if (s) -sig else sig, e))
    case _ => None
  }
}
