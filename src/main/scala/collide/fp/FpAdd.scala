package collide.fp

import chisel3._
import chisel3.util._

/** FpAdd's input: a + b, or a - b when `subtract`, rounded by `rm` (RoundingMode.hw). */
class FpAddIn(val w: Int) extends Bundle {
  val a        = UInt(w.W)
  val b        = UInt(w.W)
  val subtract = Bool()
  val rm       = UInt(3.W)
}

/** Floating-point addition/subtraction, fully pipelined, `latency` enabled cycles in to out.
  *
  * Single path: swap so the larger magnitude is `big`, align `small` right with a sticky
  * jam into 3 extra bits (guard, round, sticky: enough that a subtraction after a shift of
  * 2 or more cancels at most one bit and still leaves round and sticky exact), add or
  * subtract, normalize with a leading-zero count, then the shared RoundRaw in four stages.
  *
  * Twelve stages, each ending at a boundary where registers may go: classify the operands
  * (and compare their magnitudes), normalize subnormal ones, swap, clamp the shift, align,
  * add, count leading zeros, normalize, and the rounder's four (locate, jam, increment,
  * pack: the output). Pipeline.balanced places the `latency` registers by the stages'
  * estimated delays on `family` (FpAdd.delays), output first, so each register up to twelve
  * cuts the longest path left. Only the registers' places depend on the family; the result
  * never does.
  */
class FpAdd(val p: FpParams, val latency: Int, val family: FpgaFamily = FpgaFamily.default) extends Module {
  require(latency >= 0, s"FpAdd latency must be >= 0, got $latency")
  private val f = p.format
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new FpAddIn(f.width)))
    val out = Output(Valid(new FpOut(f.width)))
  })
  override def desiredName = s"FpAdd_${p.name}_L$latency${family.moduleSuffix}"

  private val regs = Pipeline.balanced(latency, FpAdd.delays(p, family))
  private def stage[T <: Data](i: Int, x: T): T = Pipeline(x, regs(i), io.en)
  private val ew = FpAdd.expWidth(f)
  private val xw = f.sigBits + 3 // aligned significand: sig, guard, round, sticky

  // What every stage carries besides its own data: the special cases and the result's sign.
  class Carried extends Bundle {
    val isNaN  = Bool()
    val isInf  = Bool()
    val isZero = Bool() // both operands zero
    val sign   = Bool() // sign of the result if the sum is non-zero (the larger operand's)
    val zSign  = Bool() // sign of an exact zero result when both operands are zero
    val flags  = UInt(FpFlags.width.W)
    val effSub = Bool()
    val rm     = UInt(3.W)
  }

  // ---- Stage 0: classify the operands; compare their magnitudes on the encodings ----
  // Sign-magnitude encodings order like integers, so |a| >= |b| needs no unpacking (a zero
  // operand, or a flushed subnormal, is the smallest: isZero decides those).
  class Classified extends Bundle {
    val a = new RawClass(f); val b = new RawClass(f); val subtract = Bool(); val rm = UInt(3.W)
    val hiGt = Bool(); val hiEq = Bool(); val loGe = Bool()
  }
  private val s0 = Wire(new Classified)
  s0.a := RawFloat.classify(p, io.in.bits.a)
  s0.b := RawFloat.classify(p, io.in.bits.b)
  s0.subtract := io.in.bits.subtract
  s0.rm  := io.in.bits.rm
  // In two halves, joined a stage later, so the compare's carry chain is half the word's.
  private val mw = f.width - 1
  private val hw = mw / 2
  private val (ma, mb) = (io.in.bits.a(mw - 1, 0), io.in.bits.b(mw - 1, 0))
  s0.hiGt := ma(mw - 1, hw) > mb(mw - 1, hw)
  s0.hiEq := ma(mw - 1, hw) === mb(mw - 1, hw)
  s0.loGe := ma(hw - 1, 0) >= mb(hw - 1, 0)
  private val s0r = stage(0, s0)

  // ---- Stage 1: normalize subnormal operands ----
  class Unpacked extends Bundle {
    val a = new RawFloat(f); val b = new RawFloat(f); val subtract = Bool(); val rm = UInt(3.W); val aGe = Bool()
  }
  private val s1 = Wire(new Unpacked)
  s1.a := RawFloat.normalize(p, s0r.a)
  s1.b := RawFloat.normalize(p, s0r.b)
  s1.subtract := s0r.subtract
  s1.rm  := s0r.rm
  s1.aGe := s0r.hiGt || (s0r.hiEq && s0r.loGe)
  private val s1r = stage(1, s1)

  // ---- Stage 2: specials, swap; the exponent difference both ways ----
  class Swapped extends Bundle {
    val c      = new Carried
    val exp    = SInt(ew.W) // exponent of big's top bit
    val bigSig = UInt(f.sigBits.W)
    val smlSig = UInt(f.sigBits.W)
    val dist   = UInt(ew.W) // >= 0 whenever smlSig is non-zero
  }
  private val s2 = Wire(new Swapped)
  locally {
    val a = s1r.a; val b = s1r.b
    val bSign  = b.sign ^ s1r.subtract
    val effSub = a.sign =/= bSign
    val aExp   = a.sExp.pad(ew)
    val bExp   = b.sExp.pad(ew)
    val infInvalid = a.isInf && b.isInf && effSub
    s2.c.isNaN  := a.isNaN || b.isNaN || infInvalid
    s2.c.isInf  := a.isInf || b.isInf
    s2.c.isZero := a.isZero && b.isZero
    s2.c.flags  := Mux(a.isSNaN || b.isSNaN || infInvalid, FpFlags.Invalid.U, 0.U)
    // x + (-x) = +0 except in round-down; (+0) + (+0) = +0, (-0) + (-0) = -0.
    s2.c.zSign  := Mux(effSub, s1r.rm === RoundingMode.RDN.hw, a.sign)
    s2.c.effSub := effSub
    s2.c.rm     := s1r.rm
    // Larger magnitude first; a zero operand is the smallest.
    val aBig = b.isZero || (!a.isZero && s1r.aGe)
    s2.c.sign := Mux(a.isInf, a.sign, Mux(b.isInf, bSign, Mux(aBig, a.sign, bSign)))
    s2.exp    := Mux(aBig, aExp, bExp)
    s2.bigSig := Mux(aBig, a.sig, b.sig)
    s2.smlSig := Mux(Mux(aBig, b.isZero, a.isZero), 0.U, Mux(aBig, b.sig, a.sig))
    // Both differences at once, so the swap selects one instead of waiting for it.
    s2.dist   := Mux(aBig, (aExp - bExp).asUInt, (bExp - aExp).asUInt)
  }
  private val s2r = stage(2, s2)

  // ---- Stage 3: clamp the shift (a compare, so the shifter's stage starts from registers) ----
  private val jw = log2Ceil(xw + 2)
  class Clamped extends Bundle {
    val c = new Carried; val exp = SInt(ew.W); val bigSig = UInt(f.sigBits.W); val smlSig = UInt(f.sigBits.W)
    val d = UInt(jw.W); val far = Bool()
  }
  private val s3 = Wire(new Clamped)
  s3.c      := s2r.c
  s3.exp    := s2r.exp
  s3.bigSig := s2r.bigSig
  s3.smlSig := s2r.smlSig
  private val (clamped, far) = RoundRaw.clampJam(s2r.dist, xw)
  s3.d      := clamped
  s3.far    := far
  private val s3r = stage(3, s3)

  // ---- Stage 4: align ----
  class Aligned extends Bundle {
    val c = new Carried; val exp = SInt(ew.W); val bigSig = UInt(xw.W); val smlSig = UInt(xw.W)
  }
  private val s4 = Wire(new Aligned)
  s4.c      := s3r.c
  s4.exp    := s3r.exp
  s4.bigSig := Cat(s3r.bigSig, 0.U(3.W))
  s4.smlSig := RoundRaw.jamBy(Cat(s3r.smlSig, 0.U(3.W)), s3r.d, s3r.far)
  private val s4r = stage(4, s4)

  // ---- Stage 5: add ----
  class Summed extends Bundle { val c = new Carried; val exp = SInt(ew.W); val sum = UInt((xw + 1).W) }
  private val s5 = Wire(new Summed)
  s5.c   := s4r.c
  s5.exp := s4r.exp
  s5.sum := Mux(s4r.c.effSub, s4r.bigSig -& s4r.smlSig, s4r.bigSig +& s4r.smlSig)
  private val s5r = stage(5, s5)

  // ---- Stage 6: count leading zeros ----
  class Counted extends Bundle {
    val c = new Carried; val exp = SInt(ew.W); val sum = UInt((xw + 1).W); val lz = UInt(log2Ceil(xw + 2).W)
    val sumZero = Bool()
  }
  private val s6 = Wire(new Counted)
  s6.c       := s5r.c
  s6.exp     := s5r.exp
  s6.sum     := s5r.sum
  s6.lz      := PriorityEncoder(Reverse(s5r.sum))
  s6.sumZero := s5r.sum === 0.U
  private val s6r = stage(6, s6)

  // ---- Stage 7: normalize ----
  private val s7 = Wire(new RoundIn(f, ew))
  private val rm7 = s6r.c.rm
  locally {
    val c    = s6r.c
    val norm = (s6r.sum << s6r.lz)(xw, 0) // top bit at xw (when sum != 0)
    s7.isNaN  := c.isNaN
    s7.isInf  := c.isInf && !c.isNaN
    s7.isZero := !c.isNaN && !c.isInf && (c.isZero || s6r.sumZero)
    s7.sign   := Mux(c.isZero, c.zSign, Mux(s6r.sumZero, c.rm === RoundingMode.RDN.hw, c.sign))
    s7.sExp   := s6r.exp + 1.S - s6r.lz.zext
    s7.sig    := Cat(norm(xw, xw - f.sigBits), norm(xw - f.sigBits - 1, 0).orR)
    s7.flags  := c.flags
  }
  private val s7r  = stage(7, s7)
  private val rm7r = stage(7, rm7)

  // ---- Stages 8 to 11: round ----
  private val s8r  = stage(8, RoundRaw.locate(p, s7r, rm7r))
  private val s9r  = stage(9, RoundRaw.jam(p, s8r))
  private val s10r = stage(10, RoundRaw.increment(p, s9r))
  io.out.bits  := stage(11, RoundRaw.pack(p, s10r))
  io.out.valid := Pipeline.valid(io.in.valid, latency, io.en)
}

object FpAdd {
  /** Room for the exponent + 1 and the normalize shift. */
  def expWidth(f: FloatFormat): Int = f.rawExpWidth + 2

  /** Estimated delay of each of the twelve stages on `fam` (FpgaFamily's model, ps). */
  def delays(p: FpParams, fam: FpgaFamily): Seq[Double] = {
    val f = p.format; val ew = expWidth(f); val xw = f.sigBits + 3
    val raw = RawFloat.delays(p, fam)
    Seq(
      math.max(raw(0), fam.adder((f.width - 1) - (f.width - 1) / 2)),
      raw(1),
      fam.adder(ew) + fam.luts(2),
      fam.adder(ew), // the clamp: compares with constants, which Yosys builds on the carry chain
      fam.shifter(log2Ceil(2 * xw + 2)) + fam.reduce(xw),
      fam.adder(xw + 1) + fam.luts(1),
      fam.lzc(xw + 1),
      math.max(fam.shifter(log2Ceil(xw + 2)), fam.adder(ew)) + fam.reduce(xw - f.sigBits),
    ) ++ RoundRaw.delays(fam, f, ew)
  }

  /** The smallest latency whose stages fit `mhz` on `fam`, or Left with the longest stage (ps). */
  def latencyFor(p: FpParams, fam: FpgaFamily, mhz: Double): Either[Double, Int] =
    Pipeline.latencyFor(fam.budget(mhz), delays(p, fam))
}
