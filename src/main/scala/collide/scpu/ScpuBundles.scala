package collide.scpu

import chisel3._
import collide.fp._

// The SCPU's stage boundaries as explicit bundles (docs/scpu.md, "Structure").

/** What travels beside the numbers from input to output unchanged or OR-ed. */
class ScpuMeta(val tagBits: Int) extends Bundle {
  val tag       = UInt(tagBits.W)
  val nonFinite = Bool()                 // a NaN or infinity among the link-format inputs
  val flags     = UInt(FpFlags.width.W)  // flags raised so far on the path that counts
}

/** One pair in the compute format (after ScpuConvertIn). */
class ComputePair(val w: Int, tagBits: Int) extends Bundle {
  val x1 = UInt(w.W); val y1 = UInt(w.W); val z1 = UInt(w.W); val r1 = UInt(w.W)
  val x2 = UInt(w.W); val y2 = UInt(w.W); val z2 = UInt(w.W); val r2 = UInt(w.W)
  val meta = new ScpuMeta(tagBits)
}

/** The distance unit's input: the difference p1 - p2. */
class DistanceIn(val w: Int) extends Bundle {
  val dx = UInt(w.W); val dy = UInt(w.W); val dz = UInt(w.W)
}

/** The distance and its path's flags (at the unit's dLatency). */
class DistanceD(val w: Int) extends Bundle {
  val d     = UInt(w.W)
  val flags = UInt(FpFlags.width.W)
}

/** The normal's factors, n = (ux, uy, uz) * w (at the unit's wLatency); flags of the operators
  * only the contact path uses (the reciprocal). */
class DistanceW(val fw: Int) extends Bundle {
  val ux = UInt(fw.W); val uy = UInt(fw.W); val uz = UInt(fw.W)
  val w     = UInt(fw.W)
  val flags = UInt(FpFlags.width.W)
}

/** The selected result in the compute format, zero fields when there is no hit. `d` and
  * `w` (the distance and the normal's factor, n = (p1 - p2) * w) are set for a Contact only:
  * from them and the inputs a host rebuilds pos, n and depth with + and x alone (the AFU's
  * derived record layout, docs/afu-interface.md). */
class ComputeResult(val w: Int, tagBits: Int) extends Bundle {
  val hit  = Bool()
  val kind = UInt(2.W)
  val px = UInt(w.W); val py = UInt(w.W); val pz = UInt(w.W)
  val nx = UInt(w.W); val ny = UInt(w.W); val nz = UInt(w.W)
  val depth = UInt(w.W)
  val d = UInt(w.W); val nw = UInt(w.W)
  val meta  = new ScpuMeta(tagBits)
}
