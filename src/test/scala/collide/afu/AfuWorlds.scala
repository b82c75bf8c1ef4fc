package collide.afu

import collide.fp.FpFlags
import collide.scpu.ScpuConfig
import collide.scpu.model.{ScpuModel, ScpuResult}

/** Random sphere worlds in real floating point, and the records ScpuModel expects for them. */
object AfuWorlds {
  /** The record the AFU writes for an SCPU result (docs/afu-interface.md, record flags). */
  def record(lay: BufferLayout, r: ScpuResult, pair: Int): AfuRecord = {
    val arith = (r.flags & (FpFlags.Overflow | FpFlags.Invalid)) != 0
    val values = if (lay.records.fields == RecordLayout.fullFields) r.fields else r.derived
    AfuRecord(values, pair, (if (r.hit) 1 else 0) | (r.kind << 1) | (if (r.nonFinite) 8 else 0) | (if (arith) 16 else 0))
  }

  def expect(cfg: ScpuConfig, world: World): Int => AfuRecord = {
    val m = ScpuModel(cfg)
    k => {
      val (i, j) = world.pairs(k)
      val Seq(x1, y1, z1, r1) = world.spheres(i); val Seq(x2, y2, z2, r2) = world.spheres(j)
      record(world.lay, m.collide(x1, y1, z1, r1, x2, y2, z2, r2, BigInt(k)), k)
    }
  }

  /** Spheres in a box (about one pair in six collides), with some coincident pairs (i, i),
    * exactly grazing pairs, copies, and, when `specials`, NaN / infinite / huge values and
    * out-of-range indices. */
  def random(rnd: scala.util.Random, cfg: AfuConfig, nPairs: Int, dense: Boolean, specials: Boolean): World = {
    val maxSpheres = cfg.maxSpheres
    val lf = cfg.scpu.linkFormat
    def bits(v: Double) = ScpuModel.fromDouble(lf, v)
    val ns = 2 + rnd.nextInt(math.min(maxSpheres, 300) - 1)
    val side = 3.0 + rnd.nextDouble() * 3
    val sp = Array.tabulate(ns) { _ =>
      Array(rnd.nextDouble() * side, rnd.nextDouble() * side, rnd.nextDouble() * side, 0.1 + rnd.nextDouble() * 0.8)
    }
    // grazing: sphere 1 at sphere 0 + (3, 4, 0) * s with radii 2s and 3s: d = 5s = r1 + r2
    if (ns >= 2) { val s = 0.125; sp(1) = Array(sp(0)(0) + 3 * s, sp(0)(1) + 4 * s, sp(0)(2), 3 * s); sp(0)(3) = 2 * s }
    if (specials && ns >= 6) {
      sp(2)(0) = Double.NaN; sp(3)(3) = Double.PositiveInfinity; sp(4)(1) = Double.NegativeInfinity
      sp(5) = Array(1e30, -1e30, 1e30, 1.0)
    }
    val spheres = sp.toIndexedSeq.map(s => s.toSeq.map(bits))
    val pairs = (0 until nPairs).map { _ =>
      rnd.nextInt(20) match {
        case 0 => val i = rnd.nextInt(ns); (i, i)
        case 1 => (0, 1)
        case 2 if specials => (rnd.nextInt(ns), ns + rnd.nextInt(65536 - ns))
        case _ => (rnd.nextInt(ns), rnd.nextInt(ns))
      }
    }
    World(cfg.layout, spheres, pairs, dense, lanes = cfg.puc.lanes)
  }
}
