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
  * subtract, normalize with a leading-zero count, then the shared RoundRaw.
  * Pipeline cuts (Pipeline.placement over 3 boundaries, latest first): after round (the
  * output), before round (after add/normalize), after align.
  */
class FpAdd(val p: FpParams, val latency: Int) extends Module {
  require(latency >= 0, s"FpAdd latency must be >= 0, got $latency")
  private val f = p.format
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new FpAddIn(f.width)))
    val out = Output(Valid(new FpOut(f.width)))
  })
  override def desiredName = s"FpAdd_${p.name}_L$latency"

  private val cuts = Pipeline.placement(latency, 3) // (after align, before round, output)
  private val ew   = f.rawExpWidth + 2              // room for exp+1 and the normalize shift
  private val xw   = f.sigBits + 3                  // aligned significand: sig, guard, round, sticky

  // ---- Stage 1: unpack, specials, swap, align ----
  val a = RawFloat(p, io.in.bits.a)
  val b = RawFloat(p, io.in.bits.b)
  private val bSign  = b.sign ^ io.in.bits.subtract
  private val effSub = a.sign =/= bSign
  private val aExp   = a.sExp.pad(ew)
  private val bExp   = b.sExp.pad(ew)

  class Aligned extends Bundle {
    val isNaN   = Bool()
    val isInf   = Bool()
    val isZero  = Bool()
    val sign    = Bool() // sign of the result if the sum is non-zero (the larger operand's)
    val zSign   = Bool() // sign of an exact zero result when both operands are zero
    val flags   = UInt(FpFlags.width.W)
    val effSub  = Bool()
    val exp     = SInt(ew.W) // exponent of big's top bit
    val bigSig  = UInt(xw.W)
    val smlSig  = UInt(xw.W)
    val rm      = UInt(3.W)
  }
  val s1 = Wire(new Aligned)
  private val infInvalid = a.isInf && b.isInf && effSub
  s1.isNaN  := a.isNaN || b.isNaN || infInvalid
  s1.isInf  := a.isInf || b.isInf
  s1.isZero := a.isZero && b.isZero
  s1.flags  := Mux(a.isSNaN || b.isSNaN || infInvalid, FpFlags.Invalid.U, 0.U)
  // x + (-x) = +0 except in round-down; (+0) + (+0) = +0, (-0) + (-0) = -0.
  s1.zSign  := Mux(effSub, io.in.bits.rm === RoundingMode.RDN.hw, a.sign)
  s1.effSub := effSub
  s1.rm     := io.in.bits.rm
  // Larger magnitude first; a zero operand is the smallest.
  private val aBig = b.isZero || (!a.isZero && (aExp > bExp || (aExp === bExp && a.sig >= b.sig)))
  private val bigExp = Mux(aBig, aExp, bExp)
  private val smlExp = Mux(aBig, bExp, aExp)
  private val bigSig = Mux(aBig, a.sig, b.sig)
  private val smlSig = Mux(Mux(aBig, b.isZero, a.isZero), 0.U, Mux(aBig, b.sig, a.sig))
  s1.sign   := Mux(a.isInf, a.sign, Mux(b.isInf, bSign, Mux(aBig, a.sign, bSign)))
  s1.exp    := bigExp
  s1.bigSig := Cat(bigSig, 0.U(3.W))
  private val dist = (bigExp - smlExp).asUInt // >= 0 whenever smlSig is non-zero
  s1.smlSig := RoundRaw.shiftRightJam(Cat(smlSig, 0.U(3.W)), dist)

  private val v0 = io.in.valid
  private val s1r = Pipeline(s1, cuts(0), io.en)

  // ---- Stage 2: add, normalize ----
  private val sum = Mux(s1r.effSub, s1r.bigSig -& s1r.smlSig, s1r.bigSig +& s1r.smlSig) // xw+1 bits
  private val lz  = PriorityEncoder(Reverse(sum))
  private val norm = (sum << lz)(xw, 0) // top bit at xw (when sum != 0)
  val s2 = Wire(new Bundle { val r = new RoundIn(f, ew); val rm = UInt(3.W) })
  private val sumZero = sum === 0.U
  s2.r.isNaN  := s1r.isNaN
  s2.r.isInf  := s1r.isInf && !s1r.isNaN
  s2.r.isZero := !s1r.isNaN && !s1r.isInf && (s1r.isZero || sumZero)
  s2.r.sign   := Mux(s1r.isZero, s1r.zSign, Mux(sumZero, s1r.rm === RoundingMode.RDN.hw, s1r.sign))
  s2.r.sExp   := s1r.exp + 1.S - lz.zext
  s2.r.sig    := Cat(norm(xw, xw - f.sigBits), norm(xw - f.sigBits - 1, 0).orR)
  s2.r.flags  := s1r.flags
  s2.rm       := s1r.rm
  private val s2r = Pipeline(s2, cuts(1), io.en)

  // ---- Stage 3: round ----
  private val rounded = RoundRaw(p, s2r.r, s2r.rm)
  io.out.bits  := Pipeline(rounded, cuts(2), io.en)
  io.out.valid := Pipeline.valid(v0, latency, io.en)
}
