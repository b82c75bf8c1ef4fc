package collide.fp.model

import collide.fp._

/** Golden square root: IEEE squareRoot (sqrt(-0) = -0; sqrt of a negative or of -inf is invalid).
  * Bit-exact with [[collide.fp.FpSqrt]] of the same parameters (see RootModel). */
object FpSqrtModel {
  def apply(p: FpParams, alg: RootAlgorithm, a: BigInt, rm: RoundingMode): FpResult =
    RootModel(RootOp.Sqrt, p, alg, a, rm)
}
