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

/** What the rounder's stages hand on (RoundRaw.locate, jam, increment, pack): the specials, whether the
  * result is tiny (then denormalized) or flushed, and the exponent fields and overflow tests for
  * both outcomes of the increment's carry, so the last stage is one significand adder and selects. */
class RoundCommon(val f: FloatFormat) extends Bundle {
  val isNaN  = Bool()
  val isInf  = Bool()
  val isZero = Bool()
  val sign   = Bool()
  val flags  = UInt(FpFlags.width.W)
  val rm     = UInt(3.W)
  val tiny   = Bool()
  val flush  = Bool()
  val toInf  = Bool()
  val exp0   = UInt(f.expBits.W)
  val exp1   = UInt(f.expBits.W)
  val over0  = Bool()
  val over1  = Bool()

  /** Drives these fields from another stage's. */
  def pass(from: RoundCommon): Unit = {
    isNaN := from.isNaN; isInf := from.isInf; isZero := from.isZero; sign := from.sign
    flags := from.flags; rm := from.rm; tiny := from.tiny; flush := from.flush; toInf := from.toInf
    exp0 := from.exp0; exp1 := from.exp1; over0 := from.over0; over1 := from.over1
  }
}

/** After RoundRaw.locate: the significand, and how far to shift it if tiny (clamped; `far`
  * when the shift passes every bit). */
class RoundAt(f: FloatFormat) extends RoundCommon(f) {
  val sig  = UInt((f.sigBits + 2).W)
  val dist = UInt(log2Ceil(f.sigBits + 4).W)
  val far  = Bool()
}

/** After RoundRaw.jam: the significand to round, its round bit and its sticky bit. */
class RoundMid(f: FloatFormat) extends RoundCommon(f) {
  val m   = UInt(f.sigBits.W)
  val rnd = Bool()
  val stk = Bool()
}

/** After RoundRaw.increment: the rounded significand (its top bit the increment's carry). */
class RoundInc(f: FloatFormat) extends RoundCommon(f) {
  val m1      = UInt((f.sigBits + 1).W)
  val inexact = Bool()
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
    val (d, far) = clampJam(dist, x.getWidth)
    jamBy(x, d, far)
  }

  /** The distance [[jamBy]] takes for a `w`-bit value: clamped to at most w + 1, and whether it
    * was above w (every bit falls off). */
  def clampJam(dist: UInt, w: Int): (UInt, Bool) = (Mux(dist > (w + 1).U, (w + 1).U, dist), dist > w.U)

  /** shiftRightJam with the distance already clamped to at most w + 1 (`d`) and `far` when
    * the distance is above w, so a pipeline can compute them a stage earlier. */
  def jamBy(x: UInt, d: UInt, far: Bool): UInt = {
    val w    = x.getWidth
    val wide = Cat(x, 0.U(w.W)) >> d // high w bits: kept, low w bits: shifted out
    val kept = wide(2 * w - 1, w)
    val lost = wide(w - 1, 0).orR || (far && x.orR)
    kept | lost
  }

  /** Rounds and packs in one combinational step: [[locate]], [[jam]], [[increment]], [[pack]]. */
  def apply(p: FpParams, in: RoundIn, rm: UInt): FpOut = pack(p, increment(p, jam(p, locate(p, in, rm))))

  /** The rounder's first stage: is the result tiny, how far to denormalize it, and the
    * exponent fields for either carry of the increment (adders and compares only). */
  def locate(p: FpParams, in: RoundIn, rm: UInt): RoundAt = {
    val f   = p.format
    val ew  = in.expWidth
    val w   = f.sigBits + 2
    val out = Wire(new RoundAt(f))
    out.tiny := in.sExp < f.minExp.S(ew.W)
    val dist = (f.minExp.S(ew.W) - in.sExp).asUInt
    val (clamped, far) = clampJam(dist, w)
    out.dist := clamped
    out.far  := far
    out.sig  := in.sig
    out.flush := out.tiny && (!p.subnormals).B
    out.toInf := MuxLookup(rm, true.B)(Seq(
      RoundingMode.RTZ.hw -> false.B,
      RoundingMode.RDN.hw -> in.sign,
      RoundingMode.RUP.hw -> !in.sign
    ))
    out.exp0   := (in.sExp +& f.bias.S).asUInt(f.expBits - 1, 0)
    out.exp1   := (in.sExp +& (f.bias + 1).S).asUInt(f.expBits - 1, 0)
    out.over0  := in.sExp > f.maxExp.S
    out.over1  := in.sExp >= f.maxExp.S
    out.isNaN  := in.isNaN
    out.isInf  := in.isInf
    out.isZero := in.isZero
    out.sign   := in.sign
    out.flags  := in.flags
    out.rm     := rm
    out
  }

  /** The rounder's second stage: a tiny result shifted into the subnormal range, jamming what
    * falls off into the sticky bit. */
  def jam(p: FpParams, in: RoundAt): RoundMid = {
    val f   = p.format
    val out = Wire(new RoundMid(f))
    out.pass(in)
    val sig = Mux(in.tiny, jamBy(in.sig, in.dist, in.far), in.sig)
    out.m   := sig(f.sigBits + 1, 2)
    out.rnd := sig(1)
    out.stk := sig(0)
    out
  }

  /** The rounder's third stage: whether to add one, and the increment. */
  def increment(p: FpParams, in: RoundMid): RoundInc = {
    val f   = p.format
    val out = Wire(new RoundInc(f))
    out.pass(in)
    val inexact = in.rnd || in.stk
    val up = MuxLookup(in.rm, false.B)(Seq(
      RoundingMode.RNE.hw -> (in.rnd && (in.stk || in.m(0))),
      RoundingMode.RTZ.hw -> false.B,
      RoundingMode.RDN.hw -> (inexact && in.sign),
      RoundingMode.RUP.hw -> (inexact && !in.sign),
      RoundingMode.RMM.hw -> in.rnd
    ))
    out.m1      := in.m +& up
    out.inexact := inexact
    out
  }

  /** The rounder's last stage: the exponent the increment's carry picks, the packing and the
    * flags. */
  def pack(p: FpParams, in: RoundInc): FpOut = {
    val f   = p.format
    val out = Wire(new FpOut(f.width))
    val m1    = in.m1
    val inexact = in.inexact
    val carry = m1(f.sigBits)
    val frac  = m1(f.fracBits - 1, 0)
    val overflow = !in.tiny && Mux(carry, in.over1, in.over0)
    val biased = Mux(in.tiny, m1(f.fracBits).asUInt, Mux(carry, in.exp1, in.exp0))
    val finiteBits = Cat(in.sign, biased, frac)

    val infBits = Cat(in.sign, Fill(f.expBits, 1.U(1.W)), 0.U(f.fracBits.W))
    val maxBits = Cat(in.sign, Fill(f.expBits - 1, 1.U(1.W)), 0.U(1.W), Fill(f.fracBits, 1.U(1.W)))
    val zeroBits = Cat(in.sign, 0.U((f.width - 1).W))
    val nanBits  = f.canonicalNaN.U(f.width.W)

    val nx = FpFlags.Inexact.U; val uf = FpFlags.Underflow.U; val of = FpFlags.Overflow.U
    when(in.isNaN) {
      out.bits := nanBits; out.flags := in.flags
    }.elsewhen(in.isInf) {
      out.bits := infBits; out.flags := in.flags
    }.elsewhen(in.isZero) {
      out.bits := zeroBits; out.flags := in.flags
    }.elsewhen(in.flush) {
      out.bits := zeroBits; out.flags := in.flags | uf | nx
    }.elsewhen(overflow) {
      out.bits := Mux(in.toInf, infBits, maxBits); out.flags := in.flags | of | nx
    }.otherwise {
      out.bits  := finiteBits
      out.flags := in.flags | Mux(inexact, nx, 0.U) | Mux(in.tiny && inexact, uf, 0.U)
    }
    out
  }

  /** Estimated delays of [[locate]], [[jam]], [[increment]] and [[pack]] for a result of `f`
    * whose RoundIn exponent is `ew` bits (FpgaFamily's model, ps). */
  def delays(fam: FpgaFamily, f: FloatFormat, ew: Int): Seq[Double] = Seq(
    fam.adder(ew) + fam.luts(2), // the distance's subtract, then its clamp: a compare with a constant, LUTs
    fam.shifter(log2Ceil(f.sigBits + 4)) + fam.reduce(f.sigBits + 2) + fam.luts(1),
    fam.luts(1) + fam.adder(f.sigBits + 1),
    fam.luts(3))
}
