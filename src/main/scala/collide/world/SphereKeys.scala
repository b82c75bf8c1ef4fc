package collide.world

import chisel3._
import chisel3.util._
import collide.fp.{FpParams, Pipeline, RawFloat}

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
  require(latency >= 0 && latency <= 2, s"SphereKeys latency must be 0..2, got $latency")
  require(isPow2(bp.marginDen), s"margin denominator ${bp.marginDen} must be a power of two in hardware")
  override def desiredName = s"SphereKeys_${p.name}_c${bp.cellBits}_f${bp.filterFracBits}_m${bp.marginNum}d${bp.marginDen}_e${bp.cellSteps}_l$latency"
  val io = IO(new SphereKeysIO(p, bp))
  private val f = p.format
  private val raw = io.in.sphere.map(b => RawFloat(p, b))
  private val level = io.in.level
  private val odd = if (bp.cellSteps == 2) level(0) else false.B // an edge of 1.5 * 2^(k-1), k = ceil(L / 2)
  private val k = SphereKeys.filterExp(level)

  /** floor(v * 2^-s) of a finite raw value, as SInt(w), and whether it overflowed w bits. */
  private def floorScaled(v: RawFloat, s: SInt, w: Int): (SInt, Bool) = {
    val t = (v.sExp -& f.fracBits.S) -& s // v = sig * 2^t
    val left = t >= 0.S
    val lAmt = Mux(t > (w + 1).S, (w + 1).U, t.asUInt)(log2Ceil(w + 2) - 1, 0)
    val rNeg = (0.S -& t).asUInt
    val rAmt = Mux(rNeg > (f.sigBits + 1).U, (f.sigBits + 1).U, rNeg)(log2Ceil(f.sigBits + 2) - 1, 0)
    val shiftedL = (v.sig << lAmt)(f.sigBits + w + 1, 0)
    val shiftedR = v.sig >> rAmt
    val sticky = (v.sig & ((1.U << rAmt) - 1.U)(f.sigBits - 1, 0)).orR
    val mag = Mux(left, shiftedL, shiftedR.pad(f.sigBits + w + 2))
    val up = !left && sticky && v.sign // floor of a negative inexact value rounds away from zero
    val m = mag +& up.asUInt
    val over = m >= (BigInt(1) << (w - 1)).U
    val sv = Mux(v.sign, (0.S -& m.zext), m.zext)
    (Mux(v.isZero, 0.S(w.W), sv(w - 1, 0).asSInt), !v.isZero && over)
  }

  private val nonFinite = raw.map(r => r.isNaN || r.isInf).reduce(_ || _)
  // floor(v / 2^k), or floor(v / 2^(k-2)) then floor(. / 3): 1.5 * 2^(k-1) = 3 * 2^(k-2).
  private val wideBits = bp.cellBits + 2
  private val cellsAndOver = raw.take(3).map { v =>
    val (c, o) = floorScaled(v, Mux(odd, k -& 2.S, k), wideBits)
    (if (bp.cellSteps == 2) Mux(odd, SphereKeys.floorDiv3(c), c) else c, o)
  }
  private val limit = bp.cellLimit
  private val cellOverflow = cellsAndOver.map { case (c, o) => o || c > limit.S || c < (-limit).S }.reduce(_ || _)
  private val qs = raw.take(3).map(floorScaled(_, k -& bp.filterFracBits.S, SphereKeys.qWidth(bp)))

  // qr = ceil(r * num / den * 2^(F-k)), saturated; 0 for r <= 0.
  private val r = raw(3)
  private val numBits = log2Ceil(bp.marginNum + 1)
  private val rNum = r.sig * bp.marginNum.U(numBits.W) // exact: sig * num
  private val tq = (r.sExp -& (f.fracBits + log2Ceil(bp.marginDen)).S) -& (k -& bp.filterFracBits.S)
  private val qW = SphereKeys.qWidth(bp)
  private val rw = f.sigBits + numBits
  private val qrL = Mux(tq > qW.S, qW.U, tq.asUInt)(log2Ceil(qW + 1) - 1, 0)
  private val qrRneg = (0.S -& tq).asUInt
  private val qrR = Mux(qrRneg > (rw + 1).U, (rw + 1).U, qrRneg)(log2Ceil(rw + 2) - 1, 0)
  private val qrLeft = (rNum << qrL)
  private val qrRight = (rNum >> qrR) +& (rNum & ((1.U << qrR) - 1.U)(rw - 1, 0)).orR.asUInt
  private val qrWide = Mux(tq >= 0.S, qrLeft, qrRight.pad(qrLeft.getWidth))
  private val qrMax = ((BigInt(1) << qW) - 1).U
  private val qr = Mux(r.isZero || r.sign, 0.U, Mux(qrWide > qrMax, qrMax, qrWide(qW - 1, 0)))

  // The least k with 2^k >= v = 2 r num / den: exponent of a = 2 sig num, ceiling, rebased
  // (a - 1 < 2^B, B its bit length). The odd level 2k - 1 (an edge of 1.5 * 2^(k-1)) holds
  // the sphere iff a <= 3 * 2^(B-2), i.e. iff the bit of a - 1 below its leading one is 0
  // (a >= 18, so B >= 5).
  private val x = (rNum << 1) - 1.U
  private val lead = Log2(x)
  private val needK = (r.sExp -& f.fracBits.S) +& (lead +& 1.U).zext -& log2Ceil(bp.marginDen).S
  private val oddFits = if (bp.cellSteps == 2) !(x >> (lead - 1.U))(0) else false.B
  private val need = (needK << 1) -& oddFits.asUInt.zext

  // top: |v| < 2^(sExp + 1) for a normalized raw value.
  private val coordTops = raw.take(3).map(c => (c.isZero, c.sExp +& 1.S))
  private val (topNone, top) = coordTops.reduce { (a, b) =>
    (a._1 && b._1, Mux(a._1, b._2, Mux(b._1, a._2, Mux(a._2 > b._2, a._2, b._2))))
  }

  private val en = true.B
  io.out.valid := Pipeline.valid(io.in.valid, latency, en)
  io.out.cell := Pipeline(VecInit(cellsAndOver.map(_._1(bp.cellBits - 1, 0).asSInt)), latency, en)
  io.out.cellOverflow := Pipeline(cellOverflow, latency, en)
  io.out.q := Pipeline(VecInit(qs.map(_._1)), latency, en)
  io.out.qr := Pipeline(qr, latency, en)
  io.out.need := Pipeline(need.asTypeOf(SInt(SphereKeys.kWidth(p).W)), latency, en)
  io.out.needNone := Pipeline(r.isZero || r.sign, latency, en)
  io.out.nonFinite := Pipeline(nonFinite, latency, en)
  io.out.top := Pipeline(top.asTypeOf(SInt(SphereKeys.kWidth(p).W)), latency, en)
  io.out.topNone := Pipeline(topNone, latency, en)
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

  /** floor(c / 3) of a signed c, exactly: biased to u = c + 3 * 2^(w-1) >= 0 (a multiple of
    * three more, so floor(u / 3) = floor(c / 3) + 2^(w-1)), then u / 3 as a multiply by
    * ceil(2^(n+2) / 3) and a shift, exact for every u below 2^n (Granlund and Montgomery). */
  def floorDiv3(c: SInt): SInt = {
    val w = c.getWidth
    val n = w + 1
    val bias = (BigInt(3) << (w - 1))
    val u = (c.pad(n + 1).asUInt +& bias.U)(n - 1, 0)
    val m = ((BigInt(1) << (n + 2)) + 2) / 3
    val q = (u * m.U) >> (n + 2)
    (q.zext -& (BigInt(1) << (w - 1)).S)(w - 1, 0).asSInt
  }
}
