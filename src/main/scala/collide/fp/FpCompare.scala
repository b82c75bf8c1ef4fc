package collide.fp

import chisel3._
import chisel3.util._

/** FpCompare's input. */
class FpCompareIn(val w: Int) extends Bundle {
  val a = UInt(w.W)
  val b = UInt(w.W)
}

/** Quiet comparison result: exactly one of lt / eq / gt / unordered is set. min and max
  * are IEEE 754-2019 minimumNumber / maximumNumber style: a NaN operand yields the other
  * operand (canonical NaN if both are NaN), -0 < +0 for min/max only; both as bit patterns.
  */
class FpCompareOut(val w: Int) extends Bundle {
  val lt        = Bool()
  val eq        = Bool()
  val gt        = Bool()
  val unordered = Bool()
  val min       = UInt(w.W)
  val max       = UInt(w.W)
  val flags     = UInt(FpFlags.width.W)
}

/** Floating-point quiet comparison (IEEE compareQuiet*): NV only for signaling NaN
  * operands; -0 == +0; with subnormals flushed (p.subnormals = false) subnormal operands
  * compare as zero of their sign. Sign-magnitude encodings order like integers once zeros
  * are merged, so no unpacking is needed. All `latency` registers sit at the output (the
  * logic is one comparator deep).
  */
class FpCompare(val p: FpParams, val latency: Int) extends Module {
  require(latency >= 0, s"FpCompare latency must be >= 0, got $latency")
  private val f = p.format
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new FpCompareIn(f.width)))
    val out = Output(Valid(new FpCompareOut(f.width)))
  })
  override def desiredName = s"FpCompare_${p.name}_L$latency"

  private val ra = RawFloat(p, io.in.bits.a)
  private val rb = RawFloat(p, io.in.bits.b)
  // Magnitudes with zeros (and flushed subnormals) merged to 0 and the sign dropped for zeros.
  private val magA = Mux(ra.isZero, 0.U, io.in.bits.a(f.width - 2, 0))
  private val magB = Mux(rb.isZero, 0.U, io.in.bits.b(f.width - 2, 0))
  private val negA = ra.sign && !ra.isZero
  private val negB = rb.sign && !rb.isZero
  private val unordered = ra.isNaN || rb.isNaN
  private val eqv = magA === magB && negA === negB
  private val ltv = Mux(negA =/= negB, negA, Mux(negA, magA > magB, magA < magB))

  val res = Wire(new FpCompareOut(f.width))
  res.unordered := unordered
  res.eq := !unordered && eqv
  res.lt := !unordered && ltv
  res.gt := !unordered && !eqv && !ltv
  res.flags := Mux(ra.isSNaN || rb.isSNaN, FpFlags.Invalid.U, 0.U)
  // min/max: -0 orders below +0 here, so compare with the sign of zeros kept.
  private val aBelow = Mux(ra.sign =/= rb.sign, ra.sign, Mux(ra.sign, magA > magB, magA < magB))
  // With DAZ a flushed subnormal operand is returned as the zero it reads as.
  private val aBits = Mux(ra.isZero, Cat(ra.sign, 0.U((f.width - 1).W)), io.in.bits.a)
  private val bBits = Mux(rb.isZero, Cat(rb.sign, 0.U((f.width - 1).W)), io.in.bits.b)
  private val nan = f.canonicalNaN.U(f.width.W)
  res.min := Mux(ra.isNaN && rb.isNaN, nan, Mux(ra.isNaN, bBits, Mux(rb.isNaN, aBits, Mux(aBelow, aBits, bBits))))
  res.max := Mux(ra.isNaN && rb.isNaN, nan, Mux(ra.isNaN, bBits, Mux(rb.isNaN, aBits, Mux(aBelow, bBits, aBits))))

  io.out.bits  := Pipeline(res, latency, io.en)
  io.out.valid := Pipeline.valid(io.in.valid, latency, io.en)
}
