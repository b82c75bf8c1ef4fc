package collide.fp.model

import collide.fp._

/** Shared golden datapath of FpSqrtModel, FpRecipModel and FpRsqrtModel: the special cases,
  * the exponent split, the significand core chosen by algorithm, and SoftFloat.roundPack fed
  * exactly as the RTL's RoundRaw sees the core's output.
  */
object RootModel {
  import Decoded._

  /** The significand core's golden model for `alg` (RootCoreIO contract). */
  def core(op: RootOp, alg: RootAlgorithm, sigBits: Int, sig: BigInt, expOdd: Boolean): (BigInt, Boolean) =
    alg match {
      case RootAlgorithm.DigitRecurrence => DigitRecurrenceModel.core(op, sigBits, sig, expOdd)
      case nr: RootAlgorithm.NewtonRaphson => collide.fp.RootCoreSelect.nrModel(op, nr, sigBits, sig, expOdd)
    }

  def apply(op: RootOp, p: FpParams, alg: RootAlgorithm, a: BigInt, rm: RoundingMode): FpResult = {
    val f = p.format
    val nv = FpFlags.Invalid
    def inf(neg: Boolean, flags: Int = 0)  = FpResult(f.infinity(neg), flags)
    def zero(neg: Boolean, flags: Int = 0) = FpResult(f.zero(neg), flags)
    SoftFloat.decode(p, a) match {
      case NaN(signaling) => SoftFloat.nan(p, if (signaling) nv else 0)
      case Inf(s) => op match {
        case RootOp.Sqrt  => if (s) SoftFloat.nan(p, nv) else inf(false)
        case RootOp.Recip => zero(s)
        case RootOp.Rsqrt => if (s) SoftFloat.nan(p, nv) else zero(false)
      }
      case Zero(s) => op match {
        case RootOp.Sqrt  => zero(s) // sqrt(-0) = -0
        case RootOp.Recip => inf(s, FpFlags.DivByZero)
        case RootOp.Rsqrt => inf(s, FpFlags.DivByZero) // IEEE rSqrt(-0) = -inf
      }
      case Finite(true, _, _) if op != RootOp.Recip => SoftFloat.nan(p, nv)
      case fin @ Finite(s, sig0, _) =>
        val sig    = sig0 << (f.sigBits - sig0.bitLength) // normalized: top bit set
        val e      = fin.topExp                            // a = m * 2^e, m in [1,2)
        val expOdd = Math.floorMod(e, 2) == 1
        val half   = Math.floorDiv(e, 2)
        val (w, expDec) = core(op, alg, f.sigBits, sig, expOdd)
        val dec = if (expDec) 1 else 0
        val resExp = op match {
          case RootOp.Sqrt  => half
          case RootOp.Recip => -e - dec
          case RootOp.Rsqrt => -half - dec
        }
        SoftFloat.roundPack(p, s, w >> 1, resExp - f.sigBits, w.testBit(0), rm)
    }
  }
}
