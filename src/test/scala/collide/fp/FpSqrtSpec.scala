package collide.fp

/** FpSqrt/FpRecip/FpRsqrt checks are shared (RootSpecBase); operator-specific extras go here. */
class FpSqrtSpec extends RootSpecBase(RootOp.Sqrt) { behavior of "FpSqrt" }
