package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** Turns the difference (dx, dy, dz) into the distance d (on io.d, dLatency cycles after the
  * input) and the normal's factors n = (ux, uy, uz) * w (on io.w, wLatency cycles after the
  * input). One implementation per DistanceMethod; [[DistanceUnit.apply]] picks it.
  */
abstract class DistanceUnit(val cfg: ScpuConfig) extends Module {
  private val width = cfg.format.width
  val io = IO(new Bundle {
    val en = Input(Bool())
    val in = Input(Valid(new DistanceIn(width)))
    val d  = Output(Valid(new DistanceD(width)))
    val w  = Output(Valid(new DistanceW(width)))
  })
  val dLatency: Int = cfg.dLatency
  val wLatency: Int = cfg.wLatency
  protected val ops = new FpOps(cfg, io.en)
}

object DistanceUnit {
  def apply(cfg: ScpuConfig): DistanceUnit = cfg.distance match {
    case DistanceMethod.SqrtThenRecip => Module(new SqrtRecipDistance(cfg))
    case DistanceMethod.Rsqrt         => Module(new RsqrtDistance(cfg))
    case DistanceMethod.Robust        => Module(new RobustDistance(cfg))
  }
}
