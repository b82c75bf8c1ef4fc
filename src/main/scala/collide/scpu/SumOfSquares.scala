package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** d2 = (dx*dx + dy*dy) + dz*dz in ODE's order (dCalcPointsDistance3): three FpMul, then two
  * FpAdd; dz*dz waits one adder latency. Flags: OR of all five operators.
  * Latency: cfg.sumSqLatency = mul + 2 * add.
  */
class SumOfSquares(cfg: ScpuConfig) extends Module {
  private val w = cfg.format.width
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new DistanceIn(w)))
    val out = Output(Valid(new FpOut(w)))
  })
  val latency: Int = cfg.sumSqLatency
  override def desiredName = s"SumOfSquares_${cfg.id}"

  private val ops = new FpOps(cfg, io.en)
  private val la = cfg.addLatency
  private val lm = cfg.mulLatency
  private val sx = ops.mul(io.in.bits.dx, io.in.bits.dx, io.in.valid)
  private val sy = ops.mul(io.in.bits.dy, io.in.bits.dy, io.in.valid)
  private val sz = ops.mul(io.in.bits.dz, io.in.bits.dz, io.in.valid)
  private val s  = ops.add(sx.bits.bits, sy.bits.bits, sx.valid)
  private val szD = ops.delay(sz.bits, lm, lm + la)
  private val d2 = ops.add(s.bits.bits, szD.bits, s.valid)
  private val flags = ops.delay(sx.bits.flags | sy.bits.flags | sz.bits.flags, lm, lm + 2 * la) |
    ops.delay(s.bits.flags, lm + la, lm + 2 * la) | d2.bits.flags
  io.out.valid      := d2.valid
  io.out.bits.bits  := d2.bits.bits
  io.out.bits.flags := flags
}
