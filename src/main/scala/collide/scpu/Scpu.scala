package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** Sphere Collision Processing Unit: ODE's dCollideSpheres on one pair per cycle.
  *
  * io.in takes a pair in the link format (binary32, or binary64 for compute formats wider
  * than binary32) and a tag; io.out gives the result `cfg.latency` enabled cycles later (see
  * ScpuOut: fields zero when there is no hit). Every register advances on one enable
  * en = !out.valid || out.ready, and in.ready = en: a stalled output holds the whole pipeline,
  * and a pair is accepted whenever the pipeline moves. Stages: ScpuConvertIn (link -> compute),
  * ScpuDatapath (the arithmetic, with a DistanceUnit per cfg.distance), ScpuConvertOut.
  * Golden model: collide.scpu.model.ScpuModel(cfg). docs/scpu.md describes knobs and flags.
  */
class Scpu(val cfg: ScpuConfig) extends Module {
  val io = IO(new Bundle {
    val in  = Flipped(Decoupled(new ScpuIn(cfg.linkWidth, cfg.tagBits)))
    val out = Decoupled(new ScpuOut(cfg.linkWidth, cfg.tagBits))
  })
  /** Cycles from a pair accepted to its result (all stalls excluded). */
  val latency: Int = cfg.latency
  override def desiredName = s"Scpu_${cfg.id}"

  private val en = Wire(Bool())

  private val cin = Module(new ScpuConvertIn(cfg))
  cin.io.en := en
  cin.io.in.valid := io.in.valid
  cin.io.in.bits  := io.in.bits

  private val core = Module(new ScpuDatapath(cfg))
  core.io.en := en
  core.io.in := cin.io.out

  private val cout = Module(new ScpuConvertOut(cfg))
  cout.io.en := en
  cout.io.in := core.io.out

  require(cin.latency + core.latency + cout.latency == latency, s"Scpu ${cfg.name}: stage latencies disagree with ScpuConfig")

  en := !cout.io.out.valid || io.out.ready
  io.in.ready  := en
  io.out.valid := cout.io.out.valid
  io.out.bits  := cout.io.out.bits
}
