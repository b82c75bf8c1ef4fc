package collide.fp

import chisel3._
import chisel3.util._

/** Operand bundle of the one-operand root-type operators (FpSqrt, FpRecip, FpRsqrt). */
class FpRootIn(val w: Int) extends Bundle {
  val a  = UInt(w.W)
  val rm = UInt(3.W)
}

/** How an operator's `latency` (the total, input to output) is split:
  *  - 1 register after RoundRaw (the output) once latency >= 1,
  *  - 1 register between the significand core and RoundRaw once latency >= 2,
  *  - the rest, latency - 2, inside the significand core (DigitRecurrenceCore spreads them
  *    evenly over its sigBits+1 iterations; the Newton-Raphson core places its own).
  * Unpacking (RawFloat) and the special-case logic sit combinationally before the core's
  * first iteration.
  */
object RootLatency {
  def output(latency: Int): Int   = math.min(latency, 1)
  def preRound(latency: Int): Int = math.min(math.max(latency - 1, 0), 1)
  def core(latency: Int): Int     = math.max(latency - 2, 0)
}

/** The datapath shared by FpSqrt, FpRecip and FpRsqrt: unpack, special cases, exponent split,
  * a significand core picked by `alg` (RootCoreIO), result exponent, RoundRaw. Bit-exact with
  * collide.fp.model.RootModel. The operators are thin subclasses that fix `op`.
  */
abstract class FpRootUnit(val p: FpParams, val alg: RootAlgorithm, val latency: Int, val op: RootOp) extends Module {
  require(latency >= 0 && latency <= RootCoreSelect.maxOperatorLatency(op, alg),
    s"Fp${op.name.capitalize} ${alg.name}: latency must be 0..${RootCoreSelect.maxOperatorLatency(op, alg)}, got $latency")
  private val f = p.format

  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new FpRootIn(f.width)))
    val out = Output(Valid(new FpOut(f.width)))
  })

  /** Registers inside the significand core (see RootLatency). */
  val coreLatency: Int = RootLatency.core(latency)

  private val ew  = f.rawExpWidth + 1
  private val raw = RawFloat(p, io.in.bits.a)
  private val e   = raw.sExp
  private val expOdd = e(0)
  private val half   = e >> 1 // arithmetic: floor(e/2)

  // Special cases, decided on the operand alone.
  private val nv = FpFlags.Invalid.U(FpFlags.width.W)
  private val dz = FpFlags.DivByZero.U(FpFlags.width.W)
  class Side extends Bundle {
    val isNaN  = Bool()
    val isInf  = Bool()
    val isZero = Bool()
    val sign   = Bool()
    val flags  = UInt(FpFlags.width.W)
    val exp    = SInt(ew.W) // result exponent before the core's expDec
    val rm     = UInt(3.W)
  }
  private val side = Wire(new Side)
  side.rm   := io.in.bits.rm
  side.sign := raw.sign
  side.flags := Mux(raw.isSNaN, nv, 0.U)
  private val negInvalid = raw.sign && !raw.isNaN && !raw.isZero // -inf or negative finite
  op match {
    case RootOp.Sqrt =>
      side.isNaN  := raw.isNaN || negInvalid
      side.isInf  := raw.isInf && !raw.sign
      side.isZero := raw.isZero
      when(negInvalid) { side.flags := nv }
      side.exp := half
    case RootOp.Recip =>
      side.isNaN  := raw.isNaN
      side.isInf  := raw.isZero
      side.isZero := raw.isInf
      when(raw.isZero) { side.flags := dz }
      side.exp := -e
    case RootOp.Rsqrt =>
      side.isNaN  := raw.isNaN || negInvalid
      side.isInf  := raw.isZero
      side.isZero := raw.isInf && !raw.sign
      when(negInvalid) { side.flags := nv }.elsewhen(raw.isZero) { side.flags := dz }
      side.exp := -half
  }

  private val core = RootCoreSelect(op, f.sigBits, alg, coreLatency)
  core.en := io.en
  core.in.valid       := io.in.valid
  core.in.bits.sig    := raw.sig
  core.in.bits.expOdd := expOdd

  private val sideOut = Pipeline(side, coreLatency, io.en)
  private val ri = Wire(new RoundIn(f, ew))
  ri.isNaN  := sideOut.isNaN
  ri.isInf  := sideOut.isInf
  ri.isZero := sideOut.isZero
  ri.sign   := sideOut.sign && !sideOut.isNaN
  ri.flags  := sideOut.flags
  ri.sig    := core.out.bits.sig
  ri.sExp   := (if (op == RootOp.Sqrt) sideOut.exp else sideOut.exp - core.out.bits.expDec.asUInt.zext)

  private val nPre = RootLatency.preRound(latency)
  private val riR  = Pipeline(ri, nPre, io.en)
  private val rmR  = Pipeline(sideOut.rm, nPre, io.en)
  private val vR   = Pipeline.valid(core.out.valid, nPre, io.en)
  private val rounded = RoundRaw(p, riR, rmR)

  private val nOut = RootLatency.output(latency)
  io.out.bits  := Pipeline(rounded, nOut, io.en)
  io.out.valid := Pipeline.valid(vR, nOut, io.en)

  override def desiredName = s"Fp${op.name.capitalize}_${p.name}_${alg.name}_L$latency"
}
