package collide.fp

import chisel3._
import chisel3.util._

/** An unpacked operand, subnormals normalized: for finite non-zero values
  * value = (-1)^sign * sig * 2^(sExp - fracBits) with sig's top bit set.
  * The special-value flags are mutually exclusive; when one is set sExp and sig are don't-care.
  */
class RawFloat(val f: FloatFormat) extends Bundle {
  val isNaN  = Bool()
  val isSNaN = Bool()
  val isInf  = Bool()
  val isZero = Bool()
  val sign   = Bool()
  val sExp   = SInt(f.rawExpWidth.W)
  val sig    = UInt(f.sigBits.W)
}

object RawFloat {
  /** Combinational unpack. With subnormals flushed (p.subnormals = false) a subnormal input
    * reads as a zero of its sign (DAZ), matching SoftFloat.decode.
    */
  def apply(p: FpParams, bits: UInt): RawFloat = {
    val f    = p.format
    val out  = Wire(new RawFloat(f))
    val e    = bits(f.width - 2, f.fracBits)
    val frac = bits(f.fracBits - 1, 0)
    val expZero = e === 0.U
    val expOnes = e.andR
    val fracZero = frac === 0.U
    out.sign   := bits(f.width - 1)
    out.isNaN  := expOnes && !fracZero
    out.isSNaN := expOnes && !fracZero && !frac(f.fracBits - 1)
    out.isInf  := expOnes && fracZero
    out.isZero := expZero && (fracZero || (!p.subnormals).B)
    if (p.subnormals) {
      // Normalize a subnormal: shift the fraction's leading one into the hidden-bit place.
      val lz      = PriorityEncoder(Reverse(frac)) // leading zeros of the fraction
      val subSig  = (frac << (lz +& 1.U))(f.fracBits, 0)
      val subExp  = (f.minExp - 1).S(f.rawExpWidth.W) - lz.zext
      out.sig  := Mux(expZero, subSig, Cat(1.U(1.W), frac))
      out.sExp := Mux(expZero, subExp, (e.zext - f.bias.S).asSInt)
    } else {
      out.sig  := Cat(1.U(1.W), frac)
      out.sExp := (e.zext - f.bias.S).asSInt
    }
    out
  }
}
