package collide.world

import chisel3._
import chisel3.util._
import collide.fp.{FpParams, FpgaFamily, Pipeline, RawFloat}

/** The broad phase's integer view of one sphere at cell level L, in exact arithmetic (no
  * rounding anywhere): its cell floor(v / edge) per axis (edge 2^k for L = 2k: a shift; or
  * 1.5 * 2^k for L = 2k + 1: a shift to floor(v / 2^(k-1)), then a floor division by three),
  * the box filter's fixed point floor(v * 2^(F-q)) and ceil(r * margin * 2^(F-q)) with
  * q = ceil(L / 2), and the cell level the sphere itself needs. The golden model is
  * BroadPhaseModel (cell, boxKey, need); docs/afu.md, "World mode".
  */
class SphereKeysIO(p: FpParams, bp: BroadPhaseParams) extends Bundle {
  val kWidth = SphereKeys.kWidth(p)
  val qWidth = SphereKeys.qWidth(bp)
  val in = Input(new Bundle {
    val valid = Bool()
    val sphere = Vec(4, UInt(p.width.W)) // x, y, z, r in the compute format (converted)
    val level = SInt(kWidth.W)
  })
  val out = Output(new Bundle {
    val valid = Bool()
    val cell = Vec(3, SInt(bp.cellBits.W))
    /** Some |cell| exceeds cellLimit: k was chosen too small for this sphere (an error). */
    val cellOverflow = Bool()
    val q = Vec(3, SInt(qWidth.W))
    /** Saturated at its maximum: a huge radius passes the box filter against anything. */
    val qr = UInt(qWidth.W)
    /** The least cell level that holds the sphere. */
    val need = SInt(kWidth.W)
    /** r <= 0: the sphere fits any cell (need is then don't-care). */
    val needNone = Bool()
    /** A field is NaN or infinite: the sphere is excluded. */
    val nonFinite = Bool()
    /** The least T with |x|, |y|, |z| < 2^T (what bounds k from below); don't-care if topNone. */
    val top = SInt(kWidth.W)
    /** All three coordinates are zero. */
    val topNone = Bool()
  })
}

class SphereKeys(p: FpParams, bp: BroadPhaseParams, latency: Int = 1) extends Module {
  require(latency >= 0, s"SphereKeys latency must be at least 0, got $latency")
  require(isPow2(bp.marginDen), s"margin denominator ${bp.marginDen} must be a power of two in hardware")
  override def desiredName = s"SphereKeys_${p.name}_c${bp.cellBits}_f${bp.filterFracBits}_m${bp.marginNum}d${bp.marginDen}_e${bp.cellSteps}_l$latency"
  val io = IO(new SphereKeysIO(p, bp))
  private val f = p.format
  private val en = true.B
  import SphereKeys.Seg
  /** Registers per segment boundary (the last boundary is the output), where they cut most. */
  private val regs = Pipeline.balanced(latency, SphereKeys.segmentDelays(p, bp, FpgaFamily.default))
  /** `x`, made in segment `from`, as segment `to` sees it: through the boundaries between. */
  private def at[T <: Data](x: T, from: Seg.Value, to: Seg.Value): T =
    (from.id until to.id).foldLeft(x)((acc, b) => Pipeline(acc, regs(b), en))
  /** Out through the output boundary. */
  private def out[T <: Data](x: T, from: Seg.Value): T = Pipeline(at(x, from, Seg.check), regs.last, en)
  import Seg._

  // classify: the specials and the fractions' leading zeros; the exponents' offsets from the
  // level (each shift below is the value's exponent less one of them).
  private val cls = io.in.sphere.map(b => RawFloat.classify(p, b))
  private val level = io.in.level
  private val odd0 = if (bp.cellSteps == 2) level(0) else false.B // an edge of 1.5 * 2^(k-1), k = ceil(L / 2)
  // k + c = (L + 1 + 2 c) >> 1 for k = ceil(L / 2): one adder from the level to each offset.
  private def kPlus(c: Int): SInt = (level +& (1 + 2 * c).S) >> 1
  private val cellOff0 = Mux(odd0, kPlus(f.fracBits - 2), kPlus(f.fracBits)) // floor(v / 2^k), or / 2^(k-2) then / 3
  private val qOff0 = kPlus(f.fracBits - bp.filterFracBits)
  private val qrOff0 = kPlus(f.fracBits + log2Ceil(bp.marginDen) - bp.filterFracBits)
  private val nonFinite0 = cls.map(c => c.isNaN || c.isInf).reduce(_ || _)

  // normalize: subnormals' fractions shifted up.
  private val raw = VecInit(at(VecInit(cls), classify, normalize).map(c => RawFloat.normalize(p, c)))
  private val rawE = at(raw, normalize, exponent)

  /** floor(v * 2^-(sExp - off)) of a finite raw value, as SInt(w), and whether it overflowed w
    * bits: the shift (exponent, amounts), the shift itself and the sticky bit (shift), the carry
    * of a negative inexact value (round) and the two's complement (sign). */
  private def floorScaled(vE: RawFloat, offE: SInt, w: Int): (SInt, Bool) = {
    val t = at(vE.sExp -& offE, exponent, amounts) // v = sig * 2^t
    val left = t >= 0.S
    val lAmt = Mux(t > (w + 1).S, (w + 1).U, t.asUInt)(log2Ceil(w + 2) - 1, 0)
    // -t and its clamp side by side, so the clamp does not wait for the negation
    val rAmt = Mux(t < (-(f.sigBits + 1)).S, (f.sigBits + 1).U, (0.S -& t).asUInt)(log2Ceil(f.sigBits + 2) - 1, 0)
    val v = at(vE, exponent, shift)
    val (l, lA, rA) = (at(left, amounts, shift), at(lAmt, amounts, shift), at(rAmt, amounts, shift))
    val shiftedL = (v.sig << lA)(f.sigBits + w + 1, 0)
    val shiftedR = v.sig >> rA
    val sticky = (v.sig & SphereKeys.lowMask(rA, f.sigBits)).orR
    val mag = at(Mux(l, shiftedL, shiftedR.pad(f.sigBits + w + 2)), shift, round)
    val up = at(!l && sticky && v.sign, shift, round) // floor of a negative inexact value rounds away from zero
    // Only the low w bits are added; the rest says whether mag + up reaches 2^(w-1).
    val low = at((mag(w - 1, 0) + up.asUInt)(w - 1, 0), round, sign)
    val over = at(mag(mag.getWidth - 1, w - 1).orR || (mag(w - 2, 0).andR && up), round, sign)
    val vS = at(v, shift, sign)
    val sv = Mux(vS.sign, (0.U(w.W) - low), low)
    (Mux(vS.isZero, 0.S(w.W), sv.asSInt), !vS.isZero && over)
  }

  private val nonFinite = at(nonFinite0, classify, check)
  private val wideBits = bp.cellBits + 2
  private val scaled = rawE.take(3).map(floorScaled(_, at(cellOff0, classify, exponent), wideBits))
  private val limit = bp.cellLimit
  private val oddB = at(odd0, classify, bias)
  private val cellsAndOver = scaled.map { case (c, o) =>
    val plain = at(c, sign, check)
    val cell = if (bp.cellSteps == 2) {
      val u = SphereKeys.div3Bias(at(c, sign, bias))
      val q = SphereKeys.div3Product(at(u, bias, product), wideBits)
      Mux(at(oddB, bias, check), SphereKeys.div3Unbias(at(q, product, check), wideBits), plain)
    } else plain
    // |cell| > limit, tested on c before the division (floor(c / 3) > L iff c > 3 L + 2, and
    // floor(c / 3) < -L iff c < -3 L), beside the bias, not after the product.
    val cB = at(c, sign, bias)
    val beyond = if (bp.cellSteps == 2) Mux(oddB, cB > (3 * limit + 2).S || cB < (-3 * limit).S, cB > limit.S || cB < (-limit).S)
                 else cB > limit.S || cB < (-limit).S
    (cell, at(at(o, sign, bias) || beyond, bias, check))
  }
  private val cellOverflow = cellsAndOver.map(_._2).reduce(_ || _)
  private val qs = rawE.take(3).map(floorScaled(_, at(qOff0, classify, exponent), SphereKeys.qWidth(bp)))

  // qr = ceil(r * num / den * 2^(F-k)), saturated; 0 for r <= 0.
  private val rE = rawE(3)
  private val numBits = log2Ceil(bp.marginNum + 1)
  private val qW = SphereKeys.qWidth(bp)
  private val rw = f.sigBits + numBits
  private val tq = at(rE.sExp -& at(qrOff0, classify, exponent), exponent, amounts)
  private val rA = at(rE, exponent, amounts)
  private val rNum = rA.sig * bp.marginNum.U(numBits.W) // exact: sig * num
  private val qrL = Mux(tq > qW.S, qW.U, tq.asUInt)(log2Ceil(qW + 1) - 1, 0)
  private val qrR = Mux(tq < (-(rw + 1)).S, (rw + 1).U, (0.S -& tq).asUInt)(log2Ceil(rw + 2) - 1, 0)
  private val rNumS = at(rNum, amounts, shift)
  private val (qrLS, qrRS) = (at(qrL, amounts, shift), at(qrR, amounts, shift))
  private val qrLeft = at(rNumS << qrLS, shift, round)
  private val qrRight = at(rNumS >> qrRS, shift, round) +& at((rNumS & SphereKeys.lowMask(qrRS, rw)).orR, shift, round).asUInt
  private val qrWide = Mux(at(tq >= 0.S, amounts, sign), at(qrLeft, round, sign), at(qrRight, round, sign).pad(qrLeft.getWidth))
  private val rNone = at(rA.isZero || rA.sign, amounts, sign)
  // qrWide > 2^qW - 1: a bit at or above qW.
  private val qr = Mux(rNone, 0.U, Mux(qrWide(qrWide.getWidth - 1, qW).orR, ((BigInt(1) << qW) - 1).U, qrWide(qW - 1, 0)))

  // The least k with 2^k >= v = 2 r num / den: exponent of a = 2 sig num, ceiling, rebased
  // (a - 1 < 2^B, B its bit length). The odd level 2k - 1 (an edge of 1.5 * 2^(k-1)) holds
  // the sphere iff a <= 3 * 2^(B-2), i.e. iff the bit of a - 1 below its leading one is 0
  // (a >= 18, so B >= 5). A step a segment: a - 1, its leading one, that bit and the sum, the level.
  private val x = at((rNumS << 1) - 1.U, shift, round)
  private val lead = at(Log2(x), round, sign)
  private val eOff = at(rA.sExp -& (f.fracBits + log2Ceil(bp.marginDen) - 1).S, amounts, sign)
  private val needK = at(eOff +& lead.zext, sign, bias)
  // the bit below the leading one: bit lead of 2 (a - 1), so no subtraction precedes the shift
  private val oddFits = at(if (bp.cellSteps == 2) !((at(x, round, sign) << 1) >> lead)(0) else false.B, sign, bias)
  private val need = (needK << 1) -& oddFits.asUInt.zext

  // top: |v| < 2^(sExp + 1) for a normalized raw value; the greatest of three, a compare a segment.
  private def most(a: (Bool, SInt), b: (Bool, SInt)): (Bool, SInt) =
    (a._1 && b._1, Mux(a._1, b._2, Mux(b._1, a._2, Mux(a._2 > b._2, a._2, b._2))))
  private val tops = rawE.take(3).map(c => (c.isZero, c.sExp))
  private val xy = most(tops(0), tops(1))
  private val xyz = most((at(xy._1, exponent, amounts), at(xy._2, exponent, amounts)), (at(tops(2)._1, exponent, amounts), at(tops(2)._2, exponent, amounts)))
  private val topNone = at(xyz._1, amounts, shift)
  private val top = at(xyz._2, amounts, shift) +& 1.S

  io.out.valid := Pipeline.valid(io.in.valid, latency, en)
  io.out.cell := out(VecInit(cellsAndOver.map(_._1(bp.cellBits - 1, 0).asSInt)), check)
  io.out.cellOverflow := out(cellOverflow, check)
  io.out.q := out(VecInit(qs.map(_._1)), sign)
  io.out.qr := out(qr, sign)
  io.out.need := out(need.asTypeOf(SInt(SphereKeys.kWidth(p).W)), bias)
  io.out.needNone := out(rNone, sign)
  io.out.nonFinite := out(nonFinite, check)
  io.out.top := out(top.asTypeOf(SInt(SphereKeys.kWidth(p).W)), shift)
  io.out.topNone := out(topNone, shift)
}

object SphereKeys {
  /** Wide enough for any cell level the broad phase picks: twice an exponent of the format,
    * plus slack. */
  def kWidth(p: FpParams): Int = p.format.rawExpWidth + 4
  /** A coordinate in box-filter units: a cell coordinate with filterFracBits more bits. */
  def qWidth(bp: BroadPhaseParams): Int = bp.cellBits + bp.filterFracBits + 1

  /** The box filter's exponent of cell level L, ceil(L / 2): the octave the edge lies in
    * (BroadPhaseParams.filterExp). */
  def filterExp(level: SInt): SInt = (level +& 1.S) >> 1

  /** The datapath's segments, in order; a register may sit after each (the last: the output). */
  object Seg extends Enumeration {
    val classify, normalize, exponent, amounts, shift, round, sign, bias, product, check = Value
  }

  /** Each segment's delay by a family's cell model (FpgaFamily): an estimate that places the
    * registers and picks the latency for a clock; bench/area/afu_timing.py measures the result. */
  def segmentDelays(p: FpParams, bp: BroadPhaseParams, fam: FpgaFamily): Seq[Double] = {
    val f = p.format
    val wide = f.sigBits + qWidth(bp) + 2
    val rw = f.sigBits + log2Ceil(bp.marginNum + 1)
    Seg.values.toSeq.map {
      case Seg.classify  => fam.lzc(f.fracBits)
      case Seg.normalize => fam.shifter(log2Ceil(f.fracBits + 1)) + fam.adder(f.rawExpWidth)
      case Seg.exponent  => fam.adder(f.rawExpWidth) + fam.luts(2)
      case Seg.amounts   => fam.adder(f.rawExpWidth) + fam.luts(1)
      case Seg.shift     => fam.shifter(log2Ceil(wide)) + fam.reduce(f.sigBits)
      case Seg.round     => fam.adder(math.max(qWidth(bp), rw))
      case Seg.sign      => fam.adder(qWidth(bp)) + fam.luts(1)
      case Seg.bias      => fam.adder(bp.cellBits + 3) + fam.luts(1)
      case Seg.product   => fam.dsp
      case Seg.check     => fam.luts(1) + fam.reduce(3)
    }
  }

  /** The least latency whose every stage fits `mhz` on the family, by [[segmentDelays]]. */
  def latencyFor(p: FpParams, bp: BroadPhaseParams, mhz: Double, fam: FpgaFamily = FpgaFamily.default): Int =
    Pipeline.latencyFor(fam.budget(mhz), segmentDelays(p, bp, fam)) match {
      case Right(l) => l
      case Left(worst) => throw new IllegalArgumentException(
        f"SphereKeys: one segment takes $worst%.0f ps, over the ${fam.budget(mhz)}%.0f ps a stage has at $mhz MHz on ${fam.name}")
    }

  /** The n low bits below bit `amt` set ((1 << amt) - 1): a shift of ones, no carry chain. */
  def lowMask(amt: UInt, n: Int): UInt = (~(((BigInt(1) << n) - 1).U(n.W) << amt))(n - 1, 0)

  /** floor(c / 3) of a signed c, exactly: biased to u = c + 3 * 2^(w-1) >= 0 (a multiple of
    * three more, so floor(u / 3) = floor(c / 3) + 2^(w-1)), then u / 3 as a multiply by
    * ceil(2^(n+2) / 3) and a shift, exact for every u below 2^n (Granlund and Montgomery), n =
    * w + 1; the bias comes off as a flip of bit w - 1. Three steps, so a pipeline can cut
    * between them: [[div3Bias]], [[div3Product]], [[div3Unbias]]. */
  def floorDiv3(c: SInt): SInt = div3Unbias(div3Product(div3Bias(c), c.getWidth), c.getWidth)

  def div3Bias(c: SInt): UInt = {
    val w = c.getWidth
    (c.pad(w + 2).asUInt +& (BigInt(3) << (w - 1)).U)(w, 0)
  }
  /** floor(u / 3) of u < 2^(w+1), in w bits (it is below 2^w). */
  def div3Product(u: UInt, w: Int): UInt = {
    val n = w + 1
    val m = ((BigInt(1) << (n + 2)) + 2) / 3
    ((u * m.U) >> (n + 2)).pad(w)(w - 1, 0)
  }
  /** Less 2^(w-1), in w bits: floor(c / 3) >= -2^(w-1) / 3, so the low w bits hold it. */
  def div3Unbias(q: UInt, w: Int): SInt = (q(w - 1, 0) ^ (BigInt(1) << (w - 1)).U).asSInt
}
