package collide.fp.model

import collide.fp._

/** Golden model of [[collide.fp.DigitRecurrenceCore]]. The core is correctly rounding (its
  * sigBits+1 result bits are the truncated exact value and its sticky bit is exact), so its
  * output is unique: this model computes it with exact integer square roots and divisions
  * instead of mirroring the recurrence, which keeps it independent of the RTL's algorithm.
  *
  * Contract (RootCoreIO): sig is m = sig / 2^(sigBits-1) in [1,2); x = 2m for Sqrt/Rsqrt
  * when expOdd, else x = m; v = sqrt(x), 1/x or 1/sqrt(x); expDec = (v < 1), and then w = 2v,
  * else w = v. Returns (W, expDec) with W = floor(w * 2^sigBits) * 2 + sticky (sigBits+2
  * bits: sigBits result bits, a round bit, an exact sticky bit).
  */
object DigitRecurrenceModel {
  def isqrt(n: BigInt): BigInt = BigInt(n.bigInteger.sqrt())

  def core(op: RootOp, sigBits: Int, sig: BigInt, expOdd: Boolean): (BigInt, Boolean) = {
    require(sig.bitLength == sigBits, s"DigitRecurrenceModel: sig 0x${sig.toString(16)} must have exactly $sigBits bits, top bit set")
    val one = BigInt(1) << (sigBits - 1) // m = 1
    def pack(w: BigInt, sticky: Boolean) = (w << 1) | (if (sticky) 1 else 0)
    op match {
      case RootOp.Sqrt =>
        // W = floor(sqrt(x) * 2^sigBits) = isqrt(x * 2^(2 sigBits)), x * 2^(2 sigBits) = sig << (sigBits+1+odd)
        val rad = sig << (sigBits + 1 + (if (expOdd) 1 else 0))
        val w   = isqrt(rad)
        (pack(w, w * w != rad), false)
      case RootOp.Recip =>
        if (sig == one) (pack(BigInt(1) << sigBits, sticky = false), false)
        else {
          // w = 2/m, W = floor(2^(2 sigBits) / sig)
          val num = BigInt(1) << (2 * sigBits)
          (pack(num / sig, num % sig != 0), true)
        }
      case RootOp.Rsqrt =>
        val x = sig << (if (expOdd) 1 else 0) // x = X / 2^(sigBits-1)
        if (x == one) (pack(BigInt(1) << sigBits, sticky = false), false)
        else {
          // w = 2/sqrt(x): the largest W with W^2 X <= 2^(3 sigBits + 1)
          val target = BigInt(1) << (3 * sigBits + 1)
          val w = isqrt(target / x)
          (pack(w, w * w * x != target), true)
        }
    }
  }
}
