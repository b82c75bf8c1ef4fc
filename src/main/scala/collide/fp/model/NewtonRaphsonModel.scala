package collide.fp.model

import collide.fp._

/** Golden model of [[collide.fp.NewtonRaphsonCore]]: the same integer algorithm, the same
  * widths and truncations (both read them from NewtonRaphsonCore.Plan), so it agrees with
  * the RTL bit for bit. It is not an oracle of the exact function; NewtonRaphsonErrorSpec
  * measures how far it is from one.
  */
object NewtonRaphsonModel {

  /** The core's approximation before packing: w = value / 2^fracBits in [1,2), and expDec.
    * Exposed for error measurement (error before rounding). */
  final case class Raw(value: BigInt, fracBits: Int, expDec: Boolean)

  def raw(op: RootOp, nr: RootAlgorithm.NewtonRaphson, sigBits: Int, sig: BigInt, expOdd: Boolean): Raw = {
    val plan = NewtonRaphsonCore.Plan.cached(op, sigBits, nr)
    import plan.{n, F, s}
    require(sig.bitLength == n, s"NewtonRaphsonModel: sig 0x${sig.toString(16)} must have exactly $n bits (top bit set)")
    val one    = BigInt(1)
    val odd    = plan.isRoot && expOdd
    val x      = if (odd) sig << 1 else sig // n-1 fraction bits
    val isOne  = !odd && sig == (one << (n - 1))
    val satMax = (one << F) - 1
    def sat(v: BigInt) = v.min(satMax)

    var y = (plan.seedTable(plan.index(sig, expOdd)) + (one << (s + 2))) << (F - s - 3)
    for (_ <- 0 until nr.iterations) op match {
      case RootOp.Recip =>
        val p = (x * y) >> (n - 1)
        require(p < (one << (F + 1)), s"NewtonRaphsonModel: x*y overflow (sig 0x${sig.toString(16)})")
        val e = (one << (F + 1)) - 1 - p // one's complement
        y = sat((y * e) >> F)
      case _ =>
        val y2 = (y * y) >> F
        val t  = (x * y2) >> (n - 1)
        require(t <= (BigInt(3) << F), s"NewtonRaphsonModel: x*y^2 above 3 (sig 0x${sig.toString(16)})")
        val e  = (BigInt(3) << F) - t
        y = sat((y * e) >> (F + 1))
    }
    op match {
      case RootOp.Sqrt =>
        val sq = (x * y) >> (n - 1)
        Raw(sq.max(one << F).min((one << (F + 1)) - 1), F, expDec = false)
      case _ =>
        if (isOne) Raw(one << (F - 1), F - 1, expDec = false)
        else Raw(y.max(one << (F - 1)), F - 1, expDec = true)
    }
  }

  /** Packs a Raw into RoundIn layout: n result bits, round bit, sticky = OR of the rest. */
  def pack(sigBits: Int, r: Raw): BigInt = {
    val drop = r.fracBits - (sigBits - 1) - 1
    require(drop >= 1, s"internal: no sticky bits ($drop)")
    val top = r.value >> drop
    val sticky = (r.value & ((BigInt(1) << drop) - 1)) != 0
    (top << 1) | (if (sticky) 1 else 0)
  }

  /** The core's output: (sig with sigBits+2 bits in RoundIn layout, expDec). */
  def core(op: RootOp, nr: RootAlgorithm.NewtonRaphson, sigBits: Int, sig: BigInt, expOdd: Boolean): (BigInt, Boolean) = {
    val r = raw(op, nr, sigBits, sig, expOdd)
    (pack(sigBits, r), r.expDec)
  }

  /** Both at once (the error measurement needs the raw value and the packed output). */
  def rawAndCore(op: RootOp, nr: RootAlgorithm.NewtonRaphson, sigBits: Int, sig: BigInt, expOdd: Boolean): (Raw, BigInt) = {
    val r = raw(op, nr, sigBits, sig, expOdd)
    (r, pack(sigBits, r))
  }
}
