package collide.fp

/** FpSqrt/FpRecip/FpRsqrt checks are shared (RootSpecBase); operator-specific extras go here. */
class FpRecipSpec extends RootSpecBase(RootOp.Recip) { behavior of "FpRecip" }
