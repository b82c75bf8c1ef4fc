package collide.scpu

import chisel3._

/** What the SCPU's contact `kind` field says fired (docs/afu-interface.md, record flags). */
object ContactKind {
  val Separated  = 0 // d > r1 + r2 (or the decision was NaN): no contact
  val Contact    = 1 // 0 < d <= r1 + r2
  val Coincident = 2 // d <= 0: pos p1, normal (1,0,0), depth r1 + r2
  val Invalid    = 3 // the AFU's code for a pair it could not evaluate (index out of range)
}

/** One pair of spheres in the link format (IEEE binary32 or binary64 bit patterns), with a
  * tag the SCPU carries through unchanged (the AFU puts the pair index there). Sphere 1 is
  * ODE's o1: the normal points from sphere 2 to sphere 1.
  */
class ScpuIn(val linkWidth: Int, val tagBits: Int) extends Bundle {
  val x1 = UInt(linkWidth.W); val y1 = UInt(linkWidth.W); val z1 = UInt(linkWidth.W); val r1 = UInt(linkWidth.W)
  val x2 = UInt(linkWidth.W); val y2 = UInt(linkWidth.W); val z2 = UInt(linkWidth.W); val r2 = UInt(linkWidth.W)
  val tag = UInt(tagBits.W)
}

/** One SCPU result in the link format. Fields other than hit/kind/flags/tag are zero when
  * there is no contact; `d` and `nw` (the distance and the normal's factor) only for a
  * Contact (kind 1), zero otherwise.
  */
class ScpuOut(val linkWidth: Int, val tagBits: Int) extends Bundle {
  val hit   = Bool()
  val kind  = UInt(2.W)  // ContactKind
  val px = UInt(linkWidth.W); val py = UInt(linkWidth.W); val pz = UInt(linkWidth.W)
  val nx = UInt(linkWidth.W); val ny = UInt(linkWidth.W); val nz = UInt(linkWidth.W)
  val depth = UInt(linkWidth.W)
  val d = UInt(linkWidth.W); val nw = UInt(linkWidth.W)
  val nonFinite = Bool() // a NaN or infinity among the eight inputs
  val flags = UInt(collide.fp.FpFlags.width.W) // OR of every operator's exception flags
  val tag   = UInt(tagBits.W)
}
