package collide.fp.model

import collide.fp._

/** Golden reciprocal 1/a: 1/(+-0) = +-inf with DZ, 1/(+-inf) = +-0; large operands give subnormal or zero results, subnormal ones may overflow.
  * Bit-exact with [[collide.fp.FpRecip]] of the same parameters (see RootModel). */
object FpRecipModel {
  def apply(p: FpParams, alg: RootAlgorithm, a: BigInt, rm: RoundingMode): FpResult =
    RootModel(RootOp.Recip, p, alg, a, rm)
}
