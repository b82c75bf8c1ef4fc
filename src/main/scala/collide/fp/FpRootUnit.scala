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
  *  - then the core's own, up to `coreCuts` (one a digit-recurrence iteration, one a cut of the
  *    Newton-Raphson core: RootCoreSelect.cuts), so that a register first shortens the core;
  *  - then one after the unpack (before the core's first iteration), one between each two
  *    of the rounder's locate, jam, increment and pack (RoundRaw), and one between the
  *    unpack's two halves (RawFloat.classify and normalize), so that at coreCuts + 7 every
  *    stage is one iteration or one piece of the unpack or the rounder;
  *  - any more stack in the core (a digit recurrence at its output).
  */
final case class RootLatency(latency: Int, coreCuts: Int) {
  require(latency >= 0 && coreCuts >= 0)
  val output: Int   = math.min(latency, 1)
  val preRound: Int = math.min(math.max(latency - 1, 0), 1)
  private val extra = math.max(latency - 2 - coreCuts, 0)
  /** One register for the k-th boundary past the core's (0-based), once the latency reaches it. */
  private def past(k: Int): Int = if (extra > k) 1 else 0
  val unpack: Int      = past(0)
  val locateJam: Int   = past(1)
  val jamInc: Int      = past(2)
  val incPack: Int     = past(3)
  val classify: Int    = past(4)
  val core: Int        = latency - output - preRound - unpack - locateJam - jamInc - incPack - classify
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

  private val split = RootLatency(latency, RootCoreSelect.cuts(op, f.sigBits, alg))
  /** Registers inside the significand core (see RootLatency). */
  val coreLatency: Int = split.core

  private val ew  = f.rawExpWidth + 1
  private val cls = Pipeline(RawFloat.classify(p, io.in.bits.a), split.classify, io.en)
  private val raw = Pipeline(RawFloat.normalize(p, cls), split.unpack, io.en)
  private val rmIn = Pipeline(io.in.bits.rm, split.classify + split.unpack, io.en)
  private val vIn  = Pipeline.valid(io.in.valid, split.classify + split.unpack, io.en)
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
  side.rm   := rmIn
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
  core.in.valid       := vIn
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

  private val riR  = Pipeline(ri, split.preRound, io.en)
  private val rmR  = Pipeline(sideOut.rm, split.preRound, io.en)
  private val rounderRegs = Seq(split.locateJam, split.jamInc, split.incPack, split.output)
  private val at   = Pipeline(RoundRaw.locate(p, riR, rmR), split.locateJam, io.en)
  private val mid  = Pipeline(RoundRaw.jam(p, at), split.jamInc, io.en)
  private val inc  = Pipeline(RoundRaw.increment(p, mid), split.incPack, io.en)
  io.out.bits  := Pipeline(RoundRaw.pack(p, inc), split.output, io.en)
  // The core's valid covers its own registers; the rest are counted here.
  io.out.valid := Pipeline.valid(core.out.valid, split.preRound + rounderRegs.sum, io.en)

  override def desiredName = s"Fp${op.name.capitalize}_${p.name}_${alg.name}_L$latency"
}
