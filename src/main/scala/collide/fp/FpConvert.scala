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
  * Five stages (unpack, then the rounder's locate, jam, increment and pack); Pipeline.balanced places
  * the `latency` registers by their estimated delays, the output first.
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

  private val ew   = math.max(ff.rawExpWidth, tf.rawExpWidth) + 1
  private val cuts = Pipeline.balanced(latency, FpConvert.delays(from, to, ew))

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

  private val at  = Pipeline(RoundRaw.locate(to, s1r.r, s1r.rm), cuts(1), io.en)
  private val mid = Pipeline(RoundRaw.jam(to, at), cuts(2), io.en)
  private val inc = Pipeline(RoundRaw.increment(to, mid), cuts(3), io.en)
  io.out.bits  := Pipeline(RoundRaw.pack(to, inc), cuts(4), io.en)
  io.out.valid := Pipeline.valid(io.in.valid, latency, io.en)
}

object FpConvert {
  /** Its stages: unpack (and the significand cut to the target's width), then the rounder's
    * four (RoundRaw.locate, jam, increment, pack); a latency of `stages` registers each. */
  val stages: Int = 5

  /** Estimated delay of each stage on the default family (FpgaFamily's model, ps). */
  def delays(from: FpParams, to: FpParams, ew: Int): Seq[Double] = {
    val fam = FpgaFamily.default
    Seq(RawFloat.delay(from, fam) + fam.reduce(from.format.sigBits)) ++ RoundRaw.delays(fam, to.format, ew)
  }
}
