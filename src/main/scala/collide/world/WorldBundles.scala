package collide.world

import chisel3._
import chisel3.util.log2Ceil

/** An index into a Vec of n entries, cut to the Vec's index width (none for n = 1). */
object VecIndex {
  def apply(i: UInt, n: Int): UInt = if (n <= 1) 0.U else i(log2Ceil(n) - 1, 0)
}

/** Box buckets' map (BroadPhaseModel.BoxMap) as the bucket paths use it: the origin (one unit
  * below the box's least on each axis) and the linear index's radices x and x * y (the extents
  * plus one), modulo 2^hashW: a unit's place is (x - o_x) + rx (y - o_y) + rxy (z - o_z), modulo
  * the table. */
class BoxMapBits(val unitBits: Int, val hashW: Int) extends Bundle {
  val origin = Vec(3, SInt(unitBits.W))
  val rx = UInt(hashW.W)
  val rxy = UInt(hashW.W)
}

object BoxMapBits {
  /** Width of a box extent in the status (saturated there). */
  val extentW: Int = 16
}

/** One sphere as the candidate generator sees it: its index and SphereKeys' keys. */
class WorldKey(val itemW: Int, val cellBits: Int, val qWidth: Int) extends Bundle {
  val index = UInt(itemW.W)
  val cell = Vec(3, SInt(cellBits.W))
  val q = Vec(3, SInt(qWidth.W))
  val qr = UInt(qWidth.W)
}

object WorldKey {
  /** The key of sphere `index` (itemW bits) from its record. */
  def apply(itemW: Int, index: UInt, r: KeyRecord): WorldKey = {
    val k = Wire(new WorldKey(itemW, r.cellBits, r.qWidth))
    k.index := index; k.cell := r.cell; k.q := r.q; k.qr := r.qr
    k
  }
}

/** A chunk member: its key and its place in the chunk's coarse cell (x, y, z in bits 2, 1, 0:
  * its cell less the chunk's base cell; 0 in a chunk of one cell, whose base is that cell). */
class ChunkMember(val itemW: Int, val cellBits: Int, val qWidth: Int) extends Bundle {
  val key = new WorldKey(itemW, cellBits, qWidth)
  val place = UInt(3.W)
}

object ChunkMember {
  def apply(key: WorldKey, place: UInt): ChunkMember = {
    val m = Wire(new ChunkMember(key.itemW, key.cellBits, key.qWidth))
    m.key := key; m.place := place
    m
  }
}

/** A sphere streamed past the chunk, with what decides whether it pairs with a member: in the
  * grid, the visited cell it must be in and that cell's offset from the chunk's base cell
  * (-1..2 on each axis), from which each member applies the half-shell rule; in the large
  * pass (anyCell) any cell, and whether it must have the larger index (own: a large sphere
  * meeting large ones). */
class WorldProbe(val itemW: Int, val cellBits: Int, val qWidth: Int) extends Bundle {
  val key = new WorldKey(itemW, cellBits, qWidth)
  val cell = Vec(3, SInt(cellBits.W))
  val off = Vec(3, SInt(3.W))
  val anyCell = Bool()
  val own = Bool()
}

class WorldPair(val itemW: Int) extends Bundle {
  val i = UInt(itemW.W) // i < j
  val j = UInt(itemW.W)
}

/** A sphere's key record: SphereKeys' keys at this world's k and its class, as the
  * candidate generator reads it (recomputed from the sphere table, not stored). */
class KeyRecord(val cellBits: Int, val qWidth: Int) extends Bundle {
  val cell = Vec(3, SInt(cellBits.W))
  val q = Vec(3, SInt(qWidth.W))
  val qr = UInt(qWidth.W)
  val large = Bool()    // paired with every sphere by the large pass
  val excluded = Bool() // a non-finite field: never paired
}

/** What travels with a candidate generator's stream range: a chunk scan, or a visit (the
  * cell whose entries stream past the chunk, and its offset from the chunk's base cell). */
class WorldVisit(val cellBits: Int) extends Bundle {
  val scan = Bool()
  val cell = Vec(3, SInt(cellBits.W))
  val off = Vec(3, SInt(3.W))
}
