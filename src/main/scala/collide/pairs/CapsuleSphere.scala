package collide.pairs

import chisel3._
import chisel3.util._
import collide.fp._
import collide.scpu.{ComputeResult, FpOps, ScpuConfig, ScpuDatapath}

/** A capsule and a sphere in the compute format (CapsuleSphereModel's CapsuleSpherePair). */
class CapsuleSphereIn(val w: Int, val tagBits: Int) extends Bundle {
  val cx = UInt(w.W); val cy = UInt(w.W); val cz = UInt(w.W)
  val ax = UInt(w.W); val ay = UInt(w.W); val az = UInt(w.W)
  val lz = UInt(w.W); val rc = UInt(w.W)
  val sx = UInt(w.W); val sy = UInt(w.W); val sz = UInt(w.W); val rs = UInt(w.W)
  val tag = UInt(tagBits.W)
}

/** dCollideCapsuleSphere, fully pipelined on one enable: the segment stage finds the point p
  * of the capsule's axis nearest the sphere, and the SCPU's own datapath (ScpuDatapath)
  * collides the sphere (p, rc) with (s, rs), so the result is a sphere contact in every field
  * (kind, pos, normal, depth, d, w). Schedule of the segment stage (CapsuleSphereModel):
  * {{{
  *   0                 s - c (FpAdd x3); lz2 = lz 0.5 (FpMul)
  *   La                a (s - c) (FpMul x3)
  *   La+Lm             ax dx + ay dy; then + az dz (FpAdd x2, in ODE's order)
  *   3La+Lm            alpha > lz2 ? lz2 : alpha (FpCompare)
  *   3La+Lm+Lc         < -lz2 ? -lz2 : it (FpCompare)
  *   3La+Lm+2Lc        alpha a (FpMul x3); then c + alpha a (FpAdd x3)
  *   4La+2Lm+2Lc       ScpuDatapath: `coreLatency` cycles more
  * }}}
  * Its flags and `nonFinite` (over all twelve inputs) travel into the datapath's meta, which
  * ORs them into the result's. Needs an SCPU configuration without link conversion.
  */
class CapsuleSphere(cfg: ScpuConfig) extends Module {
  require(!cfg.converts, s"CapsuleSphere: SCPU ${cfg.name} converts its link values; the capsule unit takes the compute format")
  private val w  = cfg.format.width
  private val tb = cfg.tagBits
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new CapsuleSphereIn(w, tb)))
    val out = Output(Valid(new ComputeResult(w, tb)))
  })
  val latency: Int = CapsuleSphere.latency(cfg)
  override def desiredName = s"CapsuleSphere_${cfg.id}"

  private val la = cfg.addLatency
  private val lm = cfg.mulLatency
  private val lc = cfg.cmpLatency
  private val f  = cfg.format
  private val ops = new FpOps(cfg, io.en)
  private val in = io.in.bits
  private val v0 = io.in.valid
  private val c = Seq(in.cx, in.cy, in.cz)
  private val a = Seq(in.ax, in.ay, in.az)
  private val s = Seq(in.sx, in.sy, in.sz)

  private val half = (BigInt(f.bias - 1) << f.fracBits).U(w.W)
  private val diff = s.zip(c).map { case (si, ci) => ops.sub(si, ci, v0) }
  private val lz2 = ops.mul(in.lz, half, v0)
  private val m = a.zip(diff).map { case (ai, di) => ops.mul(ops.delay(ai, 0, la), di.bits.bits, di.valid) }
  private val a01 = ops.add(m(0).bits.bits, m(1).bits.bits, m(0).valid)
  private val tAlpha = 3 * la + lm
  private val alpha = ops.add(a01.bits.bits, ops.delay(m(2).bits.bits, la + lm, la + lm + la), a01.valid)
  private val lz2A = ops.delay(lz2.bits.bits, lm, tAlpha)
  private val c1 = ops.compare(alpha.bits.bits, lz2A, alpha.valid)
  private val clamp1 = Mux(c1.bits.gt, ops.delay(lz2A, tAlpha, tAlpha + lc), ops.delay(alpha.bits.bits, tAlpha, tAlpha + lc))
  private val negLz2 = ops.delay(lz2A ^ f.signBit.U(w.W), tAlpha, tAlpha + lc)
  private val c2 = ops.compare(clamp1, negLz2, c1.valid)
  private val tClamp = tAlpha + 2 * lc
  private val clamped = Mux(c2.bits.lt, ops.delay(negLz2, tAlpha + lc, tClamp), ops.delay(clamp1, tAlpha + lc, tClamp))
  private val q = a.map(ai => ops.mul(clamped, ops.delay(ai, 0, tClamp), c2.valid))
  private val tQ = tClamp + lm
  private val pt = c.zip(q).map { case (ci, qi) => ops.add(ops.delay(ci, 0, tQ), qi.bits.bits, qi.valid) }
  private val tP = tQ + la
  require(tP == CapsuleSphere.segmentLatency(cfg))

  private def special(x: UInt): Bool = { val r = RawFloat.classify(cfg.params, x); r.isNaN || r.isInf }
  private val segFlags = ops.delay(diff.map(_.bits.flags).reduce(_ | _), la, tP) | ops.delay(lz2.bits.flags, lm, tP) |
    ops.delay(m.map(_.bits.flags).reduce(_ | _), la + lm, tP) | ops.delay(a01.bits.flags, 2 * la + lm, tP) |
    ops.delay(alpha.bits.flags, tAlpha, tP) | ops.delay(c1.bits.flags, tAlpha + lc, tP) | ops.delay(c2.bits.flags, tClamp, tP) |
    ops.delay(q.map(_.bits.flags).reduce(_ | _), tQ, tP) | pt.map(_.bits.flags).reduce(_ | _)

  private val core = Module(new ScpuDatapath(cfg))
  core.io.en := io.en
  core.io.in.valid := pt.head.valid
  private val ci = core.io.in.bits
  ci.x1 := pt(0).bits.bits; ci.y1 := pt(1).bits.bits; ci.z1 := pt(2).bits.bits; ci.r1 := ops.delay(in.rc, 0, tP)
  ci.x2 := ops.delay(in.sx, 0, tP); ci.y2 := ops.delay(in.sy, 0, tP); ci.z2 := ops.delay(in.sz, 0, tP)
  ci.r2 := ops.delay(in.rs, 0, tP)
  ci.meta.tag := ops.delay(in.tag, 0, tP)
  ci.meta.nonFinite := ops.delay((c ++ a ++ s ++ Seq(in.lz, in.rc, in.rs)).map(special).reduce(_ || _), 0, tP)
  ci.meta.flags := segFlags
  io.out := core.io.out
}

object CapsuleSphere {
  /** The segment stage's cycles: a difference, a product, two sums, two compares, a product,
    * a sum. */
  def segmentLatency(cfg: ScpuConfig): Int = 4 * cfg.addLatency + 2 * cfg.mulLatency + 2 * cfg.cmpLatency
  /** Cycles from io.in to io.out: the segment stage, then the SCPU's datapath. */
  def latency(cfg: ScpuConfig): Int = segmentLatency(cfg) + cfg.coreLatency
}
