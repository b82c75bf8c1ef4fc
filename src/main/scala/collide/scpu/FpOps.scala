package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** Instantiates the project's FP operators with one SCPU configuration's parameters (format,
  * rounding mode constant, algorithm, latency) and the shared pipeline enable. Each call is
  * one operator; the result is the operator's io.out, valid travelling with the data.
  * Not a hardware block of its own: a way to keep the datapath files short.
  */
final class FpOps(cfg: ScpuConfig, en: Bool) {
  private val p  = cfg.params
  private val rm = cfg.rm.hw

  def add(a: UInt, b: UInt, v: Bool, subtract: Boolean = false): Valid[FpOut] = {
    val m = Module(new FpAdd(p, cfg.addLatency, cfg.family))
    m.io.en := en
    m.io.in.valid := v
    m.io.in.bits.a := a; m.io.in.bits.b := b
    m.io.in.bits.subtract := subtract.B; m.io.in.bits.rm := rm
    m.io.out
  }
  def sub(a: UInt, b: UInt, v: Bool): Valid[FpOut] = add(a, b, v, subtract = true)

  def mul(a: UInt, b: UInt, v: Bool): Valid[FpOut] = {
    val m = Module(new FpMul(p, cfg.mulLatency, cfg.family))
    m.io.en := en
    m.io.in.valid := v
    m.io.in.bits.a := a; m.io.in.bits.b := b; m.io.in.bits.rm := rm
    m.io.out
  }

  def compare(a: UInt, b: UInt, v: Bool): Valid[FpCompareOut] = {
    val m = Module(new FpCompare(p, cfg.cmpLatency))
    m.io.en := en
    m.io.in.valid := v
    m.io.in.bits.a := a; m.io.in.bits.b := b
    m.io.out
  }

  def convert(from: FpParams, to: FpParams, a: UInt, v: Bool): Valid[FpOut] = {
    val m = Module(new FpConvert(from, to, cfg.cvtLatency))
    m.io.en := en
    m.io.in.valid := v
    m.io.in.bits.a := a; m.io.in.bits.rm := rm
    m.io.out
  }

  private def root(m: FpRootUnit, a: UInt, v: Bool): Valid[FpOut] = {
    m.io.en := en
    m.io.in.valid := v
    m.io.in.bits.a := a; m.io.in.bits.rm := rm
    m.io.out
  }
  def sqrt(a: UInt, v: Bool): Valid[FpOut]  = root(Module(new FpSqrt(p, cfg.sqrtAlg, cfg.sqrtLat)), a, v)
  def recip(a: UInt, v: Bool): Valid[FpOut] = root(Module(new FpRecip(p, cfg.recipAlg, cfg.recipLat)), a, v)
  def rsqrt(a: UInt, v: Bool): Valid[FpOut] = root(Module(new FpRsqrt(p, cfg.rsqrtAlg, cfg.rsqrtLat)), a, v)

  /** `x` delayed from cycle `from` to cycle `to` of a schedule (delay-matching registers). */
  def delay[T <: Data](x: T, from: Int, to: Int): T = {
    require(to >= from, s"SCPU ${cfg.name}: cannot delay a value from cycle $from back to $to")
    Pipeline(x, to - from, en)
  }
  def delayValid(v: Bool, from: Int, to: Int): Bool = {
    require(to >= from, s"SCPU ${cfg.name}: cannot delay a valid from cycle $from back to $to")
    Pipeline.valid(v, to - from, en)
  }
}
