package collide.fp

import chisel3._
import chisel3.util._

/** Correctly rounding significand core for sqrt, reciprocal and rsqrt (RootCoreIO contract):
  * a restoring digit recurrence, one result bit per iteration, producing sigBits+1 bits (the
  * sigBits result bits and the round bit) and an exact sticky bit from the final remainder.
  * The first bit is always 1 (w >= 1) and is folded into the initial state, so there are
  * n = sigBits iterations.
  *
  * Per iteration (q = the result bits so far):
  *  - Sqrt (classic bit-by-bit root of sig << (sigBits+1+expOdd), two radicand bits per step):
  *    r = 4r + next two bits; if r >= 4q+1 then r -= 4q+1, q = 2q+1 else q = 2q.
  *    One (n+3)-bit subtractor.
  *  - Recip (long division of 1, or of 2 when m > 1, by m): if r >= m then r -= m, bit 1;
  *    r = 2r. One (sigBits+1)-bit subtractor.
  *  - Rsqrt (largest y with y^2 x <= 1, or 4 when x > 1, so w = 2/sqrt(x) in (1,2)):
  *    with Y the bits so far, x scaled to an integer X, the remainder R = target - Y^2 X and
  *    QX = q * X are kept scaled so no multiplier is needed: trial D = 4 QX + X; if R >= D
  *    then R -= D, QX = 2 QX + X, bit 1 else QX = 2 QX; then R = 4R. Three (2 sigBits+6)-bit
  *    adders per step. Sticky = R != 0.
  *
  * `latency` registers are spread evenly over the n iteration boundaries (Pipeline.spread), so
  * each stage holds about n / latency iterations and the last register is at the output: 0 is
  * combinational, n is one register per iteration, n + 1 also registers the initial state
  * (RootCoreSelect.cuts), more stacks extra registers at the output end. (Placing them latest first, as before, left the first n - latency iterations as one
  * combinational path: the timing proxy's slowest path in the SCPU, docs/afu.md "Timing".)
  */
class DigitRecurrenceCore(val op: RootOp, val sigBits: Int, val latency: Int) extends Module {
  require(sigBits >= 3, s"DigitRecurrenceCore: sigBits must be >= 3, got $sigBits")
  require(latency >= 0, s"DigitRecurrenceCore: latency must be >= 0, got $latency")
  val io = IO(new RootCoreIO(sigBits))
  override def desiredName = s"DigitRecurrenceCore_${op.name}_s${sigBits}_L$latency"

  /** Recurrence steps: sigBits+1 result bits, the first of which (always 1) needs no step. */
  val iterations: Int = sigBits
  private val n = iterations
  private val resBits = sigBits + 1 // result bits: sigBits of w and the round bit
  private val rWidth = op match {
    case RootOp.Sqrt  => resBits + 2
    case RootOp.Recip => sigBits + 1
    case RootOp.Rsqrt => 2 * sigBits + 6
  }
  private val auxWidth = if (op == RootOp.Rsqrt) 2 * sigBits + 3 else 1

  class State extends Bundle {
    val valid  = Bool()
    val sig    = UInt(sigBits.W)
    val expOdd = Bool()
    val expDec = Bool()
    val q      = UInt(resBits.W)
    val r      = UInt(rWidth.W)
    val aux    = UInt(auxWidth.W) // Rsqrt: QX
  }

  val sig    = io.in.bits.sig
  val expOdd = io.in.bits.expOdd && (op != RootOp.Recip).B
  val isOne  = sig === (BigInt(1) << (sigBits - 1)).U
  // w is in [1,2), so the first result bit is always 1: its step is folded into the
  // initial state (q = 1 and the remainder after subtracting), leaving sigBits iterations.
  val s0 = Wire(new State)
  s0.valid  := io.in.valid
  s0.sig    := sig
  s0.expOdd := expOdd
  s0.q      := 1.U
  s0.aux    := 0.U
  op match {
    case RootOp.Sqrt =>
      // radicand's top two bits are 1b when expOdd (x in [2,4)), else 01: r = pair - 1
      s0.expDec := false.B
      s0.r      := Mux(expOdd, 1.U +& sig(sigBits - 2), 0.U)
    case RootOp.Recip =>
      // dividend 2 (or 1 when m = 1, where 1/m = 1 exactly), in units of sig's lsb
      s0.expDec := !isOne
      s0.r      := Mux(isOne, 0.U, Cat((BigInt(1) << sigBits).U - sig, 0.U(1.W)))
    case RootOp.Rsqrt =>
      val dec = !(isOne && !expOdd)
      val x   = Mux(expOdd, Cat(sig, 0.U(1.W)), sig)
      s0.expDec := dec
      // target (4, or 1 when x = 1) in X's units, minus X (first bit accepted), scaled by 4
      val target = Mux(dec, (BigInt(4) << (sigBits - 1)).U, (BigInt(1) << (sigBits - 1)).U)
      s0.r   := Cat(target - x, 0.U(2.W))
      s0.aux := x
  }

  /** Radicand sig << (sigBits+1+expOdd), 2 resBits bits: the two bits consumed at step i
    * (the first pair went into the initial state). */
  private def radPair(st: State, i: Int): UInt = {
    val even = Cat(st.sig, 0.U((sigBits + 1).W))   // 2 sigBits + 1 bits
    val odd  = Cat(st.sig, 0.U((sigBits + 2).W))   // 2 sigBits + 2 = 2 resBits bits
    val rad  = Mux(st.expOdd, odd, Cat(0.U(1.W), even))
    rad(2 * resBits - 3 - 2 * i, 2 * resBits - 4 - 2 * i)
  }

  /** a - b in a's width and whether a >= b, from one subtraction one bit wider. */
  private def trySub(a: UInt, b: UInt): (Bool, UInt) = {
    val w = math.max(a.getWidth, b.getWidth)
    val d = a.pad(w) -& b.pad(w)
    (!d(w), d(a.getWidth - 1, 0))
  }

  private def step(st: State, i: Int): State = {
    val nx = Wire(new State)
    nx := st
    op match {
      // Each compare is the subtraction's borrow (one carry chain, not a compare beside a
      // subtractor), then a select: one chain and a LUT a step.
      case RootOp.Sqrt =>
        val r2 = Cat(st.r, radPair(st, i))
        val t  = Cat(st.q, 1.U(2.W))
        val (ge, diff) = trySub(r2, t)
        nx.r := Mux(ge, diff, r2)
        nx.q := Cat(st.q, ge)
      case RootOp.Recip =>
        val (ge, diff) = trySub(st.r, st.sig)
        nx.r := Cat(Mux(ge, diff, st.r), 0.U(1.W))
        nx.q := Cat(st.q, ge)
      case RootOp.Rsqrt =>
        val x  = Mux(st.expOdd, Cat(st.sig, 0.U(1.W)), st.sig) // X = sig << expOdd
        val d  = Cat(st.aux, 0.U(2.W)) +& x                    // 4 QX + X
        val ge = st.r >= d
        val r1 = Mux(ge, st.r - d, st.r)
        // the last step keeps the remainder unscaled (only its non-zeroness matters)
        nx.r   := (if (i == n - 1) r1 else Cat(r1, 0.U(2.W)))
        nx.aux := Cat(st.aux, 0.U(1.W)) + Mux(ge, x, 0.U)
        nx.q   := Cat(st.q, ge)
    }
    nx
  }

  // Past one register an iteration, the next goes between the initial state and the first
  // iteration (the initial remainder is a subtraction of its own); any more stack at the output.
  private val initReg = if (latency > n) 1 else 0
  private val regs = Pipeline.spread(latency - initReg, n)
  private val s0r = Wire(new State)
  s0r := Pipeline(s0, initReg, io.en)
  if (initReg > 0) s0r.valid := Pipeline.valid(s0.valid, initReg, io.en)
  val sN = (0 until n).foldLeft(s0r) { (st, i) =>
    val nx = step(st, i)
    val out = Wire(new State)
    out := Pipeline(nx, regs(i), io.en)
    if (regs(i) > 0) out.valid := Pipeline.valid(nx.valid, regs(i), io.en)
    out
  }

  io.out.valid       := sN.valid
  io.out.bits.sig    := Cat(sN.q, sN.r.orR)
  io.out.bits.expDec := sN.expDec
}
