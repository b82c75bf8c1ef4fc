package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** The compute-format datapath of dCollideSpheres, fully pipelined on one enable.
  *
  * Schedule (cycles after the input; docs/scpu.md draws it):
  *   0          dx = x1 - x2, dy, dz; rs = r1 + r2; rdiff = r2 - r1            (FpAdd)
  *   tA         distance unit: d at tD = tA + dLatency, (u, w) at tW = tA + wLatency
  *   tD         d <= rs (FpCompare); depth = rs - d; k0 = rdiff - d            (FpAdd)
  *   tD+La      k = 0.5 * k0                                                   (FpMul)
  *   tW         n = u * w                                                      (FpMul x3)
  *   tM         n * k, tM = max(k ready, n ready)                              (FpMul x3)
  *   tM+Lm      pos = p1 + n * k                                               (FpAdd x3)
  *   tOut       select: separated -> zeros; d <= 0 -> (p1, (1,0,0), rs); else (pos, n, depth),
  *              and d, w beside them for a Contact (the derived record layout)
  * Everything that skips an operator goes through delay-matching Pipeline registers.
  *
  * Flags (docs/scpu.md): always the input conversions, the differences, r1 + r2, d's path and
  * the compare; for a Contact also r2 - r1, w's path (1/d or 1/ds; rsqrt), the normal, k,
  * n * k, pos and depth; the output conversions OR their own in (ScpuConvertOut).
  */
class ScpuDatapath(cfg: ScpuConfig) extends Module {
  private val w  = cfg.format.width
  private val tb = cfg.tagBits
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new ComputePair(w, tb)))
    val out = Output(Valid(new ComputeResult(w, tb)))
  })
  val latency: Int = cfg.coreLatency
  override def desiredName = s"ScpuDatapath_${cfg.id}"

  private val ops = new FpOps(cfg, io.en)
  private val la = cfg.addLatency
  private val lm = cfg.mulLatency
  private val f  = cfg.format
  private val in = io.in.bits
  private val v0 = io.in.valid

  // Differences and radii sums.
  private val dx = ops.sub(in.x1, in.x2, v0)
  private val dy = ops.sub(in.y1, in.y2, v0)
  private val dz = ops.sub(in.z1, in.z2, v0)
  private val rs = ops.add(in.r1, in.r2, v0)
  private val rdiff = ops.sub(in.r2, in.r1, v0)
  private val tA = la

  // Distance.
  private val dist = DistanceUnit(cfg)
  dist.io.en := io.en
  dist.io.in.valid := dx.valid
  dist.io.in.bits.dx := dx.bits.bits; dist.io.in.bits.dy := dy.bits.bits; dist.io.in.bits.dz := dz.bits.bits
  private val tD = tA + dist.dLatency
  private val tW = tA + dist.wLatency
  private val d  = dist.io.d.bits.d
  private val vD = dist.io.d.valid

  // Decision, depth, k.
  private val rsD  = ops.delay(rs.bits, tA, tD)
  private val cmp  = ops.compare(d, rsD.bits, vD)
  private val tC   = tD + cfg.cmpLatency
  private val depth = ops.sub(rsD.bits, d, vD)
  private val k0   = ops.sub(ops.delay(rdiff.bits.bits, tA, tD), d, vD)
  private val half = ((BigInt(f.bias - 1)) << f.fracBits).U(w.W)
  private val k    = ops.mul(half, k0.bits.bits, k0.valid)
  private val tK   = tD + la + lm
  private val dRaw = RawFloat(cfg.params, d)
  private val dZero = dRaw.isZero || (dRaw.sign && !dRaw.isNaN) // d <= 0 (d is never negative)

  // Normal, n * k, pos.
  private val wv = dist.io.w.bits
  private val n  = Seq(wv.ux, wv.uy, wv.uz).map(u => ops.mul(u, wv.w, dist.io.w.valid))
  private val tN = tW + lm
  private val tM = math.max(tK, tN)
  private val nM = n.map(x => ops.delay(x.bits.bits, tN, tM))
  private val kM = ops.delay(k.bits.bits, tK, tM)
  private val vM = ops.delayValid(k.valid, tK, tM)
  private val nk = nM.map(x => ops.mul(x, kM, vM))
  private val p1 = Seq(in.x1, in.y1, in.z1).map(x => ops.delay(x, 0, tM + lm))
  private val pos = p1.zip(nk).map { case (a, b) => ops.add(a, b.bits.bits, b.valid) }
  private val tP = tM + lm + la
  private val tOut = math.max(tP, tC)
  require(tOut == latency, s"ScpuDatapath ${cfg.name}: schedule ($tOut) disagrees with ScpuConfig ($latency)")

  // Flags of the path that fired (see the class comment).
  private val baseFlags = ops.delay(in.meta.flags, 0, tOut) |
    ops.delay(dx.bits.flags | dy.bits.flags | dz.bits.flags | rs.bits.flags, tA, tOut) |
    ops.delay(dist.io.d.bits.flags, tD, tOut) | ops.delay(cmp.bits.flags, tC, tOut)
  private val contactFlags = ops.delay(rdiff.bits.flags, tA, tOut) | ops.delay(wv.flags, tW, tOut) |
    ops.delay(depth.bits.flags | k0.bits.flags, tD + la, tOut) | ops.delay(k.bits.flags, tK, tOut) |
    ops.delay(n.map(_.bits.flags).reduce(_ | _), tN, tOut) |
    ops.delay(nk.map(_.bits.flags).reduce(_ | _), tM + lm, tOut) |
    ops.delay(pos.map(_.bits.flags).reduce(_ | _), tP, tOut)

  // Selection.
  private val le    = ops.delay(cmp.bits.lt || cmp.bits.eq, tC, tOut)
  private val zero  = ops.delay(dZero, tD, tOut)
  private val coinc = le && zero
  private val contact = le && !zero
  private val one   = (BigInt(f.bias) << f.fracBits).U(w.W)
  private val p1O   = p1.map(x => ops.delay(x, tM + lm, tOut))
  private val posO  = pos.map(x => ops.delay(x.bits.bits, tP, tOut))
  private val nO    = nM.map(x => ops.delay(x, tM, tOut))
  private val depthO = ops.delay(depth.bits.bits, tD + la, tOut)
  private val rsO   = ops.delay(rsD.bits, tD, tOut)
  private val dO    = ops.delay(d, tD, tOut)
  private val wO    = ops.delay(wv.w, tW, tOut)
  private def pick(c: UInt, co: UInt): UInt = Mux(contact, c, Mux(coinc, co, 0.U(w.W)))

  private val o = io.out.bits
  o.hit  := le
  o.kind := Mux(contact, ContactKind.Contact.U(2.W), Mux(coinc, ContactKind.Coincident.U(2.W), ContactKind.Separated.U(2.W)))
  o.px := pick(posO(0), p1O(0)); o.py := pick(posO(1), p1O(1)); o.pz := pick(posO(2), p1O(2))
  o.nx := pick(nO(0), one);      o.ny := pick(nO(1), 0.U);      o.nz := pick(nO(2), 0.U)
  o.depth := pick(depthO, rsO)
  o.d  := Mux(contact, dO, 0.U)
  o.nw := Mux(contact, wO, 0.U)
  o.meta.tag       := ops.delay(in.meta.tag, 0, tOut)
  o.meta.nonFinite := ops.delay(in.meta.nonFinite, 0, tOut)
  o.meta.flags     := baseFlags | Mux(contact, contactFlags, 0.U)
  io.out.valid := ops.delayValid(pos.head.valid, tP, tOut)
}
