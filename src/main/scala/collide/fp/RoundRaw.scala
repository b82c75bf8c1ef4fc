package collide.fp

import chisel3._
import chisel3.util._

/** What every arithmetic core hands to the rounder: the exact result normalized, with one
  * round bit and a sticky bit jammed into the last place.
  *
  * For finite non-zero results: value = (-1)^sign * sig * 2^(sExp - sigBits - 1), sig's top bit
  * set; sig holds the sigBits result bits, then a round bit, then a sticky bit that is the OR
  * of everything below. Special results set exactly one of isNaN / isInf / isZero; `flags`
  * carries what the core already knows (invalid, divide by zero).
  */
class RoundIn(val f: FloatFormat, val expWidth: Int) extends Bundle {
  val isNaN  = Bool()
  val isInf  = Bool()
  val isZero = Bool()
  val sign   = Bool()
  val sExp   = SInt(expWidth.W)
  val sig    = UInt((f.sigBits + 2).W)
  val flags  = UInt(FpFlags.width.W)
}

/** A packed result with its exception flags. */
class FpOut(val w: Int) extends Bundle {
  val bits  = UInt(w.W)
  val flags = UInt(FpFlags.width.W)
}

/** Rounds and packs; the combinational half of every operator (hardfloat's RoundRawFN
  * idea: cores compute, one rounder rounds). Bit-exact with SoftFloat.roundPack.
  */
object RoundRaw {
  /** Shift right, OR-ing every bit shifted out into the result's last bit. */
  def shiftRightJam(x: UInt, dist: UInt): UInt = {
    val w       = x.getWidth
    val maxDist = w + 1
    val d       = Mux(dist > maxDist.U, maxDist.U, dist)
    val wide    = Cat(x, 0.U(w.W)) >> d // high w bits: kept, low w bits: shifted out
    val kept    = wide(2 * w - 1, w)
    val lost    = wide(w - 1, 0).orR || (dist > w.U && x.orR)
    kept | lost
  }

  def apply(p: FpParams, in: RoundIn, rm: UInt): FpOut = {
    val f   = p.format
    val ew  = in.expWidth
    val out = Wire(new FpOut(f.width))

    val tiny = in.sExp < f.minExp.S(ew.W)
    // Denormalize a tiny result into the subnormal range before rounding.
    val dist = (f.minExp.S(ew.W) - in.sExp).asUInt
    val sig  = Mux(tiny, shiftRightJam(in.sig, dist), in.sig)
    val m    = sig(f.sigBits + 1, 2)
    val rnd  = sig(1)
    val stk  = sig(0)
    val inexact = rnd || stk
    val up = MuxLookup(rm, false.B)(Seq(
      RoundingMode.RNE.hw -> (rnd && (stk || m(0))),
      RoundingMode.RTZ.hw -> false.B,
      RoundingMode.RDN.hw -> (inexact && in.sign),
      RoundingMode.RUP.hw -> (inexact && !in.sign),
      RoundingMode.RMM.hw -> rnd
    ))
    val m1    = m +& up
    val carry = m1(f.sigBits)
    val frac  = m1(f.fracBits - 1, 0)
    val expOut = in.sExp +& carry.zext // unbiased exponent after rounding (normal path)
    val overflow = !tiny && expOut > f.maxExp.S
    val biased = Mux(tiny, m1(f.fracBits).asUInt, (expOut +& f.bias.S).asUInt(f.expBits - 1, 0))
    val finiteBits = Cat(in.sign, biased, frac)

    val toInf = MuxLookup(rm, true.B)(Seq(
      RoundingMode.RTZ.hw -> false.B,
      RoundingMode.RDN.hw -> in.sign,
      RoundingMode.RUP.hw -> !in.sign
    ))
    val infBits = Cat(in.sign, Fill(f.expBits, 1.U(1.W)), 0.U(f.fracBits.W))
    val maxBits = Cat(in.sign, Fill(f.expBits - 1, 1.U(1.W)), 0.U(1.W), Fill(f.fracBits, 1.U(1.W)))
    val zeroBits = Cat(in.sign, 0.U((f.width - 1).W))
    val nanBits  = f.canonicalNaN.U(f.width.W)

    val nx = FpFlags.Inexact.U; val uf = FpFlags.Underflow.U; val of = FpFlags.Overflow.U
    val flush = tiny && (!p.subnormals).B
    when(in.isNaN) {
      out.bits := nanBits; out.flags := in.flags
    }.elsewhen(in.isInf) {
      out.bits := infBits; out.flags := in.flags
    }.elsewhen(in.isZero) {
      out.bits := zeroBits; out.flags := in.flags
    }.elsewhen(flush) {
      out.bits := zeroBits; out.flags := in.flags | uf | nx
    }.elsewhen(overflow) {
      out.bits := Mux(toInf, infBits, maxBits); out.flags := in.flags | of | nx
    }.otherwise {
      out.bits  := finiteBits
      out.flags := in.flags | Mux(inexact, nx, 0.U) | Mux(tiny && inexact, uf, 0.U)
    }
    out
  }
}
