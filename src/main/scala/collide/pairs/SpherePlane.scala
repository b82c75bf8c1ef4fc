package collide.pairs

import chisel3._
import chisel3.util._
import collide.fp._
import collide.scpu.{FpOps, ScpuConfig}

/** A sphere and a plane in the compute format (SpherePlaneModel's SpherePlanePair). */
class SpherePlaneIn(val w: Int, val tagBits: Int) extends Bundle {
  val cx = UInt(w.W); val cy = UInt(w.W); val cz = UInt(w.W); val r = UInt(w.W)
  val nx = UInt(w.W); val ny = UInt(w.W); val nz = UInt(w.W); val d = UInt(w.W)
  val tag = UInt(tagBits.W)
}

/** Its contact, zero fields when there is none (SpherePlaneModel's SpherePlaneResult). */
class SpherePlaneOut(val w: Int, val tagBits: Int) extends Bundle {
  val hit = Bool()
  val px = UInt(w.W); val py = UInt(w.W); val pz = UInt(w.W)
  val nx = UInt(w.W); val ny = UInt(w.W); val nz = UInt(w.W)
  val depth = UInt(w.W)
  val nonFinite = Bool()
  val flags = UInt(FpFlags.width.W)
  val tag = UInt(tagBits.W)
}

/** dCollideSpherePlane, fully pipelined: one pair a cycle on one enable, `latency` cycles from
  * io.in to io.out. ODE's order (SpherePlaneModel):
  * {{{
  *   0            mx = cx nx, my = cy ny, mz = cz nz; tx = nx r, ty, tz     (FpMul x6)
  *   Lm           s = mx + my;  pos = c - t                                  (FpAdd x4)
  *   Lm+La        k = s + mz
  *   Lm+2La       e = d - k
  *   Lm+3La       depth = e + r
  *   Lm+4La       hit = depth >= 0 (a sign test: NaN is no contact); select
  * }}}
  * Every other value waits in delay-matching Pipeline registers. The operators are the SCPU's
  * (format, rounding, algorithms and latencies from `cfg`), so a configuration pipelined for a
  * clock (ScpuConfig.atClock) gives this unit the same clock.
  */
class SpherePlane(cfg: ScpuConfig) extends Module {
  private val w  = cfg.format.width
  private val tb = cfg.tagBits
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new SpherePlaneIn(w, tb)))
    val out = Output(Valid(new SpherePlaneOut(w, tb)))
  })
  private val la = cfg.addLatency
  private val lm = cfg.mulLatency
  val latency: Int = SpherePlane.latency(cfg)
  override def desiredName = s"SpherePlane_${cfg.id}"

  private val ops = new FpOps(cfg, io.en)
  private val in = io.in.bits
  private val v0 = io.in.valid
  private val c = Seq(in.cx, in.cy, in.cz)
  private val n = Seq(in.nx, in.ny, in.nz)

  private val m = c.zip(n).map { case (ci, ni) => ops.mul(ci, ni, v0) }
  private val t = n.map(ni => ops.mul(ni, in.r, v0))
  private val s = ops.add(m(0).bits.bits, m(1).bits.bits, m(0).valid)
  private val pos = c.zip(t).map { case (ci, ti) => ops.sub(ops.delay(ci, 0, lm), ti.bits.bits, ti.valid) }
  private val k = ops.add(s.bits.bits, ops.delay(m(2).bits.bits, lm, lm + la), s.valid)
  private val e = ops.sub(ops.delay(in.d, 0, lm + 2 * la), k.bits.bits, k.valid)
  private val depth = ops.add(e.bits.bits, ops.delay(in.r, 0, lm + 3 * la), e.valid)
  private val tOut = lm + 4 * la
  require(tOut == latency)

  private val raw = RawFloat.classify(cfg.params, depth.bits.bits)
  private val hit = !raw.isNaN && (!raw.sign || raw.isZero)
  private val baseFlags = ops.delay(m.map(_.bits.flags).reduce(_ | _), lm, tOut) |
    ops.delay(s.bits.flags, lm + la, tOut) | ops.delay(k.bits.flags, lm + 2 * la, tOut) |
    ops.delay(e.bits.flags, lm + 3 * la, tOut) | depth.bits.flags
  private val contactFlags = ops.delay(t.map(_.bits.flags).reduce(_ | _), lm, tOut) |
    ops.delay(pos.map(_.bits.flags).reduce(_ | _), lm + la, tOut)
  private def special(x: UInt): Bool = { val r = RawFloat.classify(cfg.params, x); r.isNaN || r.isInf }
  private def pick(x: UInt): UInt = Mux(hit, x, 0.U(w.W))

  private val o = io.out.bits
  private val posO = pos.map(p => ops.delay(p.bits.bits, lm + la, tOut))
  private val nO = n.map(ni => ops.delay(ni, 0, tOut))
  o.hit := hit
  o.px := pick(posO(0)); o.py := pick(posO(1)); o.pz := pick(posO(2))
  o.nx := pick(nO(0)); o.ny := pick(nO(1)); o.nz := pick(nO(2))
  o.depth := pick(depth.bits.bits)
  o.nonFinite := ops.delay((c ++ n :+ in.r :+ in.d).map(special).reduce(_ || _), 0, tOut)
  o.flags := baseFlags | Mux(hit, contactFlags, 0.U)
  o.tag := ops.delay(in.tag, 0, tOut)
  io.out.valid := depth.valid
}

object SpherePlane {
  /** Cycles from io.in to io.out: a multiply and four adds in a row (the dot product's two,
    * d - k and + r). */
  def latency(cfg: ScpuConfig): Int = cfg.mulLatency + 4 * cfg.addLatency
}
