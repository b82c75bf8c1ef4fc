package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** Robust distance: E = exponent of the largest |component| of (dx, dy, dz) (0 if all are
  * zero or any is infinite or NaN); (sx, sy, sz) = (dx, dy, dz) * 2^-E, so the largest lies in
  * [1, 2) and the scaled sum of squares in [1, 12) can neither overflow nor underflow;
  * ds = sqrt(scaled d2); d = ds * 2^E (exact unless d leaves the format's range);
  * w = 1/ds, u = (sx, sy, sz), so n = u * w never meets 1/d's overflow for tiny d.
  * Components far below the largest may lose bits (or flush) when scaled; their squares lie
  * below d2's last place anyway. d's flags: scaling, sum of squares, sqrt, unscaling; w's: 1/ds.
  */
class RobustDistance(cfg: ScpuConfig) extends DistanceUnit(cfg) {
  override def desiredName = s"RobustDistance_${cfg.id}"
  private val p  = cfg.params
  private val ls = cfg.scaleLatency

  private val comps = Seq(io.in.bits.dx, io.in.bits.dy, io.in.bits.dz)
  private val raws  = comps.map(RawFloat(p, _))
  private val special = raws.map(r => r.isNaN || r.isInf).reduce(_ || _)
  private def scaler(a: UInt, e: SInt, v: Bool): (Valid[FpOut], Int) = {
    val m = Module(new Pow2Scale(p, ls))
    m.io.en := io.en
    m.io.in.valid := v
    m.io.in.bits.a := a; m.io.in.bits.e := e; m.io.in.bits.rm := cfg.rm.hw
    (m.io.out, m.eWidth)
  }
  private val eW = cfg.format.rawExpWidth + 1
  // Largest exponent among the finite non-zero components (a reduction tree of two compares).
  private val minE = (cfg.format.minSubExp - 1).S(eW.W)
  private val es = raws.map(r => Mux(r.isZero || r.isNaN || r.isInf, minE, r.sExp.pad(eW)))
  private val maxE = es.reduce((a, b) => Mux(a > b, a, b))
  private val e = Mux(special || maxE === minE, 0.S(eW.W), maxE)

  private val scaled = comps.map(c => scaler(c, (-e).asSInt.pad(eW)(eW - 1, 0).asSInt, io.in.valid)._1)
  private val ss = Module(new SumOfSquares(cfg))
  ss.io.en := io.en
  ss.io.in.valid := scaled.head.valid
  ss.io.in.bits.dx := scaled(0).bits.bits; ss.io.in.bits.dy := scaled(1).bits.bits; ss.io.in.bits.dz := scaled(2).bits.bits
  private val t2 = ls + ss.latency
  private val ds = ops.sqrt(ss.io.out.bits.bits, ss.io.out.valid)
  private val tS = t2 + cfg.sqrtLat
  private val (d, _) = scaler(ds.bits.bits, ops.delay(e, 0, tS), ds.valid)
  private val inv = ops.recip(ds.bits.bits, ds.valid)
  require(tS + ls == dLatency && tS + cfg.recipLat == wLatency, s"RobustDistance ${cfg.name}: schedule disagrees with ScpuConfig")

  private val scaleFlags = scaled.map(_.bits.flags).reduce(_ | _)
  io.d.valid      := d.valid
  io.d.bits.d     := d.bits.bits
  io.d.bits.flags := ops.delay(scaleFlags, ls, dLatency) | ops.delay(ss.io.out.bits.flags, t2, dLatency) |
    ops.delay(ds.bits.flags, tS, dLatency) | d.bits.flags
  private val u = scaled.map(s => ops.delay(s.bits.bits, ls, wLatency))
  io.w.valid      := inv.valid
  io.w.bits.ux    := u(0); io.w.bits.uy := u(1); io.w.bits.uz := u(2)
  io.w.bits.w     := inv.bits.bits
  io.w.bits.flags := inv.bits.flags
}
