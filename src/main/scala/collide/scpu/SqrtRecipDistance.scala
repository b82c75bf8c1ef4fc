package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** ODE's order: d = sqrt(d2), w = 1/d, u = (dx, dy, dz).
  * d's flags: sum of squares and sqrt; w's flags: the reciprocal.
  */
class SqrtRecipDistance(cfg: ScpuConfig) extends DistanceUnit(cfg) {
  override def desiredName = s"SqrtRecipDistance_${cfg.id}"

  private val ss = Module(new SumOfSquares(cfg))
  ss.io.en := io.en
  ss.io.in := io.in
  private val t2 = ss.latency
  private val d  = ops.sqrt(ss.io.out.bits.bits, ss.io.out.valid)
  private val tD = t2 + cfg.sqrtLat
  private val inv = ops.recip(d.bits.bits, d.valid)
  require(tD == dLatency && tD + cfg.recipLat == wLatency, s"SqrtRecipDistance ${cfg.name}: schedule disagrees with ScpuConfig")

  io.d.valid      := d.valid
  io.d.bits.d     := d.bits.bits
  io.d.bits.flags := ops.delay(ss.io.out.bits.flags, t2, tD) | d.bits.flags
  private val u = ops.delay(io.in.bits, 0, wLatency)
  io.w.valid      := inv.valid
  io.w.bits.ux    := u.dx; io.w.bits.uy := u.dy; io.w.bits.uz := u.dz
  io.w.bits.w     := inv.bits.bits
  io.w.bits.flags := inv.bits.flags
}
