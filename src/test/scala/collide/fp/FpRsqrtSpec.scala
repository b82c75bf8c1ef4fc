package collide.fp

/** FpSqrt/FpRecip/FpRsqrt checks are shared (RootSpecBase); operator-specific extras go here. */
class FpRsqrtSpec extends RootSpecBase(RootOp.Rsqrt) { behavior of "FpRsqrt" }
