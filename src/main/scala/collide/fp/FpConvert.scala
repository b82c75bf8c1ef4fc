package collide.fp

import chisel3._
import chisel3.util._

/** FpConvert's input: `a` in the source format, rounded by `rm` (RoundingMode.hw). */
class FpConvertIn(val w: Int) extends Bundle {
  val a  = UInt(w.W)
  val rm = UInt(3.W)
}

/** Converts between any two formats: widening is exact, narrowing rounds by `rm`, and
  * overflow, underflow and flushing follow `to` (subnormal inputs follow `from`: DAZ when
  * from.subnormals is false). Every NaN becomes `to`'s canonical NaN, NV on a signaling NaN.
  * The significand is truncated to to.sigBits + 1 bits with a sticky jam (or zero-padded),
  * the exponent carried as is, and the shared RoundRaw does the rest.
  * Pipeline cuts (Pipeline.placement over 2 boundaries, latest first): after round (the
  * output), then before round.
  */
class FpConvert(val from: FpParams, val to: FpParams, val latency: Int) extends Module {
  require(latency >= 0, s"FpConvert latency must be >= 0, got $latency")
  private val ff = from.format
  private val tf = to.format
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new FpConvertIn(ff.width)))
    val out = Output(Valid(new FpOut(tf.width)))
  })
  override def desiredName = s"FpConvert_${from.name}_to_${to.name}_L$latency"

  private val cuts = Pipeline.placement(latency, 2) // (before round, output)
  private val ew   = math.max(ff.rawExpWidth, tf.rawExpWidth) + 1

  private val a = RawFloat(from, io.in.bits.a)
  val s1 = Wire(new Bundle { val r = new RoundIn(tf, ew); val rm = UInt(3.W) })
  s1.r.isNaN  := a.isNaN
  s1.r.isInf  := a.isInf
  s1.r.isZero := a.isZero
  s1.r.sign   := a.sign
  s1.r.sExp   := a.sExp.pad(ew)
  private val rw = tf.sigBits + 2
  s1.r.sig := (if (ff.sigBits <= tf.sigBits + 1) {
    Cat(a.sig, 0.U((rw - ff.sigBits).W))
  } else {
    val keep = tf.sigBits + 1
    Cat(a.sig(ff.sigBits - 1, ff.sigBits - keep), a.sig(ff.sigBits - keep - 1, 0).orR)
  })
  s1.r.flags := Mux(a.isSNaN, FpFlags.Invalid.U, 0.U)
  s1.rm      := io.in.bits.rm
  private val s1r = Pipeline(s1, cuts(0), io.en)

  private val rounded = RoundRaw(to, s1r.r, s1r.rm)
  io.out.bits  := Pipeline(rounded, cuts(1), io.en)
  io.out.valid := Pipeline.valid(io.in.valid, latency, io.en)
}
