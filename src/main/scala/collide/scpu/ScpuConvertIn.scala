package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** Link format -> compute format for the eight inputs (FpConvert, rounding by cfg.rounding),
  * and the non-finite test on the link-format values (what the host sent). With the compute
  * format equal to the link format and subnormals kept nothing changes, so no converter is
  * built and the latency is 0 (cfg.inLatency).
  */
class ScpuConvertIn(cfg: ScpuConfig) extends Module {
  private val lw = cfg.linkWidth
  private val w  = cfg.format.width
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new ScpuIn(lw, cfg.tagBits)))
    val out = Output(Valid(new ComputePair(w, cfg.tagBits)))
  })
  val latency: Int = cfg.inLatency
  override def desiredName = s"ScpuConvertIn_${cfg.id}"

  private val ops = new FpOps(cfg, io.en)
  private val b = io.in.bits
  private val links = Seq(b.x1, b.y1, b.z1, b.r1, b.x2, b.y2, b.z2, b.r2)
  private val nonFinite = links.map { x => RawFloat(cfg.linkParams, x) }.map(r => r.isNaN || r.isInf).reduce(_ || _)

  private val (vals, flags, valid) =
    if (cfg.converts) {
      val c = links.map(x => ops.convert(cfg.linkParams, cfg.params, x, io.in.valid))
      (c.map(_.bits.bits), c.map(_.bits.flags).reduce(_ | _), c.head.valid)
    } else (links, 0.U(FpFlags.width.W), io.in.valid)

  private val o = io.out.bits
  Seq(o.x1, o.y1, o.z1, o.r1, o.x2, o.y2, o.z2, o.r2).zip(vals).foreach { case (d, s) => d := s }
  o.meta.tag       := ops.delay(b.tag, 0, latency)
  o.meta.nonFinite := ops.delay(nonFinite, 0, latency)
  o.meta.flags     := flags
  io.out.valid := valid
}
