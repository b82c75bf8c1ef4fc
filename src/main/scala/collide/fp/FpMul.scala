package collide.fp

import chisel3._
import chisel3.util._

/** FpMul's input: a * b rounded by `rm` (RoundingMode.hw). */
class FpMulIn(val w: Int) extends Bundle {
  val a  = UInt(w.W)
  val b  = UInt(w.W)
  val rm = UInt(3.W)
}

/** Floating-point multiplication, fully pipelined, `latency` enabled cycles in to out.
  *
  * RawFloat normalizes subnormal operands, so the significand product always has its top
  * bit at one of the two highest places: one conditional shift normalizes it. The product's
  * exponent spans about twice the format's range (two subnormals multiplied), so RoundIn's
  * exponent is one bit wider than RawFloat's; RoundRaw denormalizes or flushes tiny results.
  * Pipeline cuts (Pipeline.placement over 3 boundaries, latest first): after round (the
  * output), before round (after normalize), after the significand multiply.
  */
class FpMul(val p: FpParams, val latency: Int) extends Module {
  require(latency >= 0, s"FpMul latency must be >= 0, got $latency")
  private val f = p.format
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new FpMulIn(f.width)))
    val out = Output(Valid(new FpOut(f.width)))
  })
  override def desiredName = s"FpMul_${p.name}_L$latency"

  private val cuts = Pipeline.placement(latency, 3) // (after multiply, before round, output)
  private val ew   = f.rawExpWidth + 2

  // ---- Stage 1: unpack, specials, multiply ----
  val a = RawFloat(p, io.in.bits.a)
  val b = RawFloat(p, io.in.bits.b)
  class Product extends Bundle {
    val isNaN  = Bool()
    val isInf  = Bool()
    val isZero = Bool()
    val sign   = Bool()
    val flags  = UInt(FpFlags.width.W)
    val exp    = SInt(ew.W)           // a.sExp + b.sExp: exponent of the product's bit 2*sigBits-2
    val prod   = UInt((2 * f.sigBits).W)
    val rm     = UInt(3.W)
  }
  val s1 = Wire(new Product)
  private val invalid = (a.isInf && b.isZero) || (a.isZero && b.isInf)
  s1.isNaN  := a.isNaN || b.isNaN || invalid
  s1.isInf  := a.isInf || b.isInf
  s1.isZero := a.isZero || b.isZero
  s1.sign   := a.sign ^ b.sign
  s1.flags  := Mux(a.isSNaN || b.isSNaN || invalid, FpFlags.Invalid.U, 0.U)
  s1.exp    := a.sExp.pad(ew) + b.sExp.pad(ew)
  s1.prod   := a.sig * b.sig
  s1.rm     := io.in.bits.rm
  private val s1r = Pipeline(s1, cuts(0), io.en)

  // ---- Stage 2: normalize (product in [1,4) -> [1,2)) ----
  private val top = s1r.prod(2 * f.sigBits - 1)
  private val pw  = 2 * f.sigBits
  // sigBits + 1 leading bits then the rest jammed into a sticky bit.
  private val hi  = Mux(top, s1r.prod(pw - 1, pw - f.sigBits - 1), s1r.prod(pw - 2, pw - f.sigBits - 2))
  private val lo  = Mux(top, s1r.prod(pw - f.sigBits - 2, 0).orR, s1r.prod(pw - f.sigBits - 3, 0).orR)
  val s2 = Wire(new Bundle { val r = new RoundIn(f, ew); val rm = UInt(3.W) })
  s2.r.isNaN  := s1r.isNaN
  s2.r.isInf  := s1r.isInf && !s1r.isNaN
  s2.r.isZero := s1r.isZero && !s1r.isNaN && !s1r.isInf
  s2.r.sign   := s1r.sign
  s2.r.sExp   := s1r.exp + top.zext
  s2.r.sig    := Cat(hi, lo)
  s2.r.flags  := s1r.flags
  s2.rm       := s1r.rm
  private val s2r = Pipeline(s2, cuts(1), io.en)

  // ---- Stage 3: round ----
  private val rounded = RoundRaw(p, s2r.r, s2r.rm)
  io.out.bits  := Pipeline(rounded, cuts(2), io.en)
  io.out.valid := Pipeline.valid(io.in.valid, latency, io.en)
}
