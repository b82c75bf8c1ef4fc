package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** Compute format -> link format for the seven contact fields and d, w. The link format holds every
  * compute-format value (ScpuConfig requires it), so these conversions are exact and raise no
  * flags; their flags are OR-ed in all the same. No hardware when the formats are equal
  * (cfg.outLatency = 0).
  */
class ScpuConvertOut(cfg: ScpuConfig) extends Module {
  private val lw = cfg.linkWidth
  private val w  = cfg.format.width
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new ComputeResult(w, cfg.tagBits)))
    val out = Output(Valid(new ScpuOut(lw, cfg.tagBits)))
  })
  val latency: Int = cfg.outLatency
  override def desiredName = s"ScpuConvertOut_${cfg.id}"

  private val ops = new FpOps(cfg, io.en)
  private val b = io.in.bits
  private val fields = Seq(b.px, b.py, b.pz, b.nx, b.ny, b.nz, b.depth, b.d, b.nw)

  private val (vals, flags, valid) =
    if (cfg.converts) {
      val c = fields.map(x => ops.convert(cfg.params, cfg.linkParams, x, io.in.valid))
      (c.map(_.bits.bits), c.map(_.bits.flags).reduce(_ | _), c.head.valid)
    } else (fields, 0.U(FpFlags.width.W), io.in.valid)

  private val o = io.out.bits
  Seq(o.px, o.py, o.pz, o.nx, o.ny, o.nz, o.depth, o.d, o.nw).zip(vals).foreach { case (d, s) => d := s }
  o.hit       := ops.delay(b.hit, 0, latency)
  o.kind      := ops.delay(b.kind, 0, latency)
  o.tag       := ops.delay(b.meta.tag, 0, latency)
  o.nonFinite := ops.delay(b.meta.nonFinite, 0, latency)
  o.flags     := ops.delay(b.meta.flags, 0, latency) | flags
  io.out.valid := valid
}
