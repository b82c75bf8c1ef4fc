package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** inv = rsqrt(d2); d = d2 * inv; w = inv, u = (dx, dy, dz). d2 = 0 and d2 = inf take d = d2
  * (sqrt's exact answers) instead of 0 * inf = NaN (IEEE 754's invalid operation; docs/scpu.md); then the rsqrt's and the
  * multiply's flags do not count. d's flags: sum of squares, and unless guarded rsqrt and the
  * multiply; w's flags: rsqrt.
  */
class RsqrtDistance(cfg: ScpuConfig) extends DistanceUnit(cfg) {
  override def desiredName = s"RsqrtDistance_${cfg.id}"

  private val ss = Module(new SumOfSquares(cfg))
  ss.io.en := io.en
  ss.io.in := io.in
  private val t2 = ss.latency
  private val d2 = ss.io.out.bits
  private val inv = ops.rsqrt(d2.bits, ss.io.out.valid)
  private val tW = t2 + cfg.rsqrtLat
  private val d2W = ops.delay(d2, t2, tW)
  private val dm = ops.mul(d2W.bits, inv.bits.bits, inv.valid)
  private val tD = tW + cfg.mulLatency
  require(tD == dLatency && tW == wLatency, s"RsqrtDistance ${cfg.name}: schedule disagrees with ScpuConfig")

  private val raw = RawFloat(cfg.params, d2.bits)
  private val guard = ops.delay(raw.isZero || raw.isInf, t2, tD)
  private val d2D = ops.delay(d2W, tW, tD)
  private val invFlagsD = ops.delay(inv.bits.flags, tW, tD)
  io.d.valid      := dm.valid
  io.d.bits.d     := Mux(guard, d2D.bits, dm.bits.bits)
  io.d.bits.flags := d2D.flags | Mux(guard, 0.U, invFlagsD | dm.bits.flags)
  private val u = ops.delay(io.in.bits, 0, wLatency)
  io.w.valid      := inv.valid
  io.w.bits.ux    := u.dx; io.w.bits.uy := u.dy; io.w.bits.uz := u.dz
  io.w.bits.w     := inv.bits.bits
  io.w.bits.flags := inv.bits.flags
}
