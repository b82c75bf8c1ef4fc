package collide.testutil

import scala.util.Random
import collide.fp.FloatFormat

/** Operand generators for floating-point specs, after Berkeley TestFloat: special values,
  * boundary exponents crossed with structured significands (runs of ones and zeros, single
  * bits, near-ties), and plain random bit patterns. Deterministic for a given rng.
  */
object FpPatterns {
  /** Special values of `f`, both signs: zeros, smallest/largest subnormal, smallest normal,
    * 1 and its neighbours, largest finite, infinities, quiet and signaling NaNs. */
  def specials(f: FloatFormat): Seq[BigInt] = {
    val one  = BigInt(f.bias) << f.fracBits
    val minN = BigInt(1) << f.fracBits
    val pos = Seq(
      BigInt(0), BigInt(1), f.fracMask, minN, minN + 1, one, one + 1, one - 1,
      one + (BigInt(1) << (f.fracBits - 1)),             // 1.5
      (BigInt(f.bias + 1) << f.fracBits),                // 2
      f.maxFinite(false), f.maxFinite(false) - 1,
      f.infinity(false),
      f.canonicalNaN,                                    // quiet NaN
      f.infinity(false) | 1,                             // signaling NaN, minimal payload
      f.infinity(false) | (f.fracMask >> 1),             // signaling NaN, full payload
      f.infinity(false) | f.fracMask                     // quiet NaN, full payload
    )
    pos ++ pos.map(_ | f.signBit)
  }

  /** Exponent field values TestFloat-style: the edges of the range and around the bias. */
  private def exponent(f: FloatFormat, rng: Random): BigInt = {
    val top = f.expMask.toInt
    rng.nextInt(12) match {
      case 0 => 0
      case 1 => 1
      case 2 => 2
      case 3 => top
      case 4 => top - 1
      case 5 => top - 2
      case 6 => f.bias
      case 7 | 8 => (f.bias + rng.nextInt(2 * f.sigBits + 5) - f.sigBits - 2).max(0).min(top)
      case 9 => 1 + rng.nextInt(f.sigBits + 2).min(top - 1) // near the subnormal boundary
      case _ => rng.nextInt(top + 1)
    }
  }

  /** Fraction field patterns: runs of ones or zeros from either end, single bits, random. */
  private def fraction(f: FloatFormat, rng: Random): BigInt = {
    val w    = f.fracBits
    val mask = f.fracMask
    def ones(k: Int) = (BigInt(1) << k) - 1
    val k = rng.nextInt(w + 1)
    rng.nextInt(10) match {
      case 0 => 0
      case 1 => mask
      case 2 => ones(k)                              // low run of ones
      case 3 => mask ^ ones(k)                       // high run of ones
      case 4 => BigInt(1) << rng.nextInt(w)          // one bit
      case 5 => mask ^ (BigInt(1) << rng.nextInt(w)) // one bit clear
      case 6 => (BigInt(w, rng.self) | ones(k)) & mask  // random, low bits forced to one
      case 7 => BigInt(w, rng.self) & ~ones(k) & mask   // random, low bits forced to zero
      case _ => BigInt(w, rng.self)
    }
  }

  /** One operand: 1/8 a special value, 1/4 random bits, the rest exponent x fraction patterns. */
  def operand(f: FloatFormat, rng: Random): BigInt = {
    val sign = if (rng.nextBoolean()) f.signBit else BigInt(0)
    rng.nextInt(8) match {
      case 0     => val s = specials(f); s(rng.nextInt(s.size))
      case 1 | 2 => BigInt(f.width, rng.self)
      case _     => sign | (exponent(f, rng) << f.fracBits) | fraction(f, rng)
    }
  }

  def operands(f: FloatFormat, rng: Random, n: Int): Seq[BigInt] = Seq.fill(n)(operand(f, rng))

  /** Pairs for addition-like operators: half independent, half with b's exponent near a's
    * (so cancellation, carries and ties in alignment are frequent). */
  def pairs(f: FloatFormat, rng: Random, n: Int): Seq[(BigInt, BigInt)] = Seq.fill(n) {
    val a = operand(f, rng)
    val b =
      if (rng.nextBoolean()) operand(f, rng)
      else {
        val ea = ((a >> f.fracBits) & f.expMask).toInt
        val eb = (ea + rng.nextInt(2 * f.sigBits + 7) - f.sigBits - 3).max(0).min(f.expMask.toInt)
        (if (rng.nextBoolean()) f.signBit else BigInt(0)) | (BigInt(eb) << f.fracBits) | fraction(f, rng)
      }
    (a, b)
  }
}
