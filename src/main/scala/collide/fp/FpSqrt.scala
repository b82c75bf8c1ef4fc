package collide.fp

/** Square root (IEEE squareRoot): sqrt(-0) = -0, sqrt(+inf) = +inf, negative operands and -inf give the canonical NaN with NV. Always correctly rounded with DigitRecurrence.
  *
  * io: en (advance), in: Valid(FpRootIn(a, rm)), out: Valid(FpOut); exactly `latency` enabled
  * cycles from in to out, one result per cycle. `latency` is the total; RootLatency says how
  * it is split (output register, pre-rounding register, the rest in the core). Golden model:
  * collide.fp.model.FpSqrtModel. desiredName: FpSqrt_<format>[_ftz]_<alg>_L<latency>.
  */
class FpSqrt(p: FpParams, alg: RootAlgorithm, latency: Int) extends FpRootUnit(p, alg, latency, RootOp.Sqrt)
