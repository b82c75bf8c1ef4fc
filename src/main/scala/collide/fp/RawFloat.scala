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

/** RawFloat's first half (RawFloat.classify): the specials, the fields, and the fraction's
  * leading zeros, so the normalizing shift can start a stage of its own. */
class RawClass(val f: FloatFormat) extends Bundle {
  val isNaN   = Bool()
  val isSNaN  = Bool()
  val isInf   = Bool()
  val isZero  = Bool()
  val sign    = Bool()
  val expZero = Bool()
  val e       = UInt(f.expBits.W)
  val frac    = UInt(f.fracBits.W)
  val lz      = UInt(log2Ceil(f.fracBits + 1).W)
}

object RawFloat {
  /** Combinational unpack: [[normalize]] of [[classify]]. With subnormals flushed
    * (p.subnormals = false) a subnormal input reads as a zero of its sign (DAZ), matching
    * SoftFloat.decode.
    */
  def apply(p: FpParams, bits: UInt): RawFloat = normalize(p, classify(p, bits))

  /** The unpack's first half: specials and the fraction's leading-zero count. */
  def classify(p: FpParams, bits: UInt): RawClass = {
    val f    = p.format
    val out  = Wire(new RawClass(f))
    val e    = bits(f.width - 2, f.fracBits)
    val frac = bits(f.fracBits - 1, 0)
    val expZero = e === 0.U
    val expOnes = e.andR
    val fracZero = frac === 0.U
    out.sign    := bits(f.width - 1)
    out.isNaN   := expOnes && !fracZero
    out.isSNaN  := expOnes && !fracZero && !frac(f.fracBits - 1)
    out.isInf   := expOnes && fracZero
    out.isZero  := expZero && (fracZero || (!p.subnormals).B)
    out.expZero := expZero
    out.e       := e
    out.frac    := frac
    out.lz      := (if (p.subnormals) PriorityEncoder(Reverse(frac)) else 0.U) // leading zeros of the fraction
    out
  }

  /** The unpack's second half: a subnormal's fraction shifted to put its leading one in the
    * hidden bit's place, and its exponent lowered to match. */
  def normalize(p: FpParams, c: RawClass): RawFloat = {
    val f   = p.format
    val out = Wire(new RawFloat(f))
    out.sign   := c.sign
    out.isNaN  := c.isNaN
    out.isSNaN := c.isSNaN
    out.isInf  := c.isInf
    out.isZero := c.isZero
    if (p.subnormals) {
      val subSig = (c.frac << (c.lz +& 1.U))(f.fracBits, 0)
      val subExp = (f.minExp - 1).S(f.rawExpWidth.W) - c.lz.zext
      out.sig  := Mux(c.expZero, subSig, Cat(1.U(1.W), c.frac))
      out.sExp := Mux(c.expZero, subExp, (c.e.zext - f.bias.S).asSInt)
    } else {
      out.sig  := Cat(1.U(1.W), c.frac)
      out.sExp := (c.e.zext - f.bias.S).asSInt
    }
    out
  }

  /** Estimated delays of [[classify]] and [[normalize]] on `fam` (FpgaFamily's model, ps):
    * with subnormals, the fraction's leading-zero count, then its shift beside the exponent's
    * adder; without, a LUT each. */
  def delays(p: FpParams, fam: FpgaFamily): Seq[Double] =
    if (p.subnormals) Seq(fam.lzc(p.format.fracBits),
      math.max(fam.shifter(log2Ceil(p.format.sigBits)), fam.adder(p.format.rawExpWidth)) + fam.luts(1))
    else Seq(fam.luts(1), fam.luts(1))

  /** The whole unpack's estimated delay. */
  def delay(p: FpParams, fam: FpgaFamily): Double = delays(p, fam).sum
}
