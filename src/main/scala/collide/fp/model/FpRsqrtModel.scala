package collide.fp.model

import collide.fp._

/** Golden reciprocal square root: IEEE rSqrt (rsqrt(+-0) = +-inf with DZ, rsqrt(+inf) = +0, negative operands invalid).
  * Bit-exact with [[collide.fp.FpRsqrt]] of the same parameters (see RootModel). */
object FpRsqrtModel {
  def apply(p: FpParams, alg: RootAlgorithm, a: BigInt, rm: RoundingMode): FpResult =
    RootModel(RootOp.Rsqrt, p, alg, a, rm)
}
