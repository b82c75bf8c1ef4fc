package collide.fp

/** Reciprocal square root (IEEE rSqrt): rsqrt(+0) = +inf and rsqrt(-0) = -inf with DZ, rsqrt(+inf) = +0, negative operands give the canonical NaN with NV. Results are always normal (no overflow or underflow in any format).
  *
  * io: en (advance), in: Valid(FpRootIn(a, rm)), out: Valid(FpOut); exactly `latency` enabled
  * cycles from in to out, one result per cycle. `latency` is the total; RootLatency says how
  * it is split (output register, pre-rounding register, the rest in the core). Golden model:
  * collide.fp.model.FpRsqrtModel. desiredName: FpRsqrt_<format>[_ftz]_<alg>_L<latency>.
  */
class FpRsqrt(p: FpParams, alg: RootAlgorithm, latency: Int) extends FpRootUnit(p, alg, latency, RootOp.Rsqrt)
