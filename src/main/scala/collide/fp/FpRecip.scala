package collide.fp

/** Reciprocal 1/a: 1/(+-0) = +-inf with DZ, 1/(+-inf) = +-0; results of large operands may be subnormal (or flush/underflow), those of subnormal operands may overflow; both are rounded exactly.
  *
  * io: en (advance), in: Valid(FpRootIn(a, rm)), out: Valid(FpOut); exactly `latency` enabled
  * cycles from in to out, one result per cycle. `latency` is the total; RootLatency says how
  * it is split (output register, pre-rounding register, the rest in the core). Golden model:
  * collide.fp.model.FpRecipModel. desiredName: FpRecip_<format>[_ftz]_<alg>_L<latency>.
  */
class FpRecip(p: FpParams, alg: RootAlgorithm, latency: Int) extends FpRootUnit(p, alg, latency, RootOp.Recip)
