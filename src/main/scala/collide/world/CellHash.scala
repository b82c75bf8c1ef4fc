package collide.world

import chisel3._
import chisel3.util._
import collide.world.model.BroadPhaseModel

/** The bucket of a cell, as BroadPhaseModel.bucket: ((cx * HashX) ^ (cy * HashY) ^
  * (cz * HashZ)) mod the used buckets; with `coarse` (coarse chunks), that hash of the coarse
  * cell (each coordinate halved, rounding down) times 8 plus the cell's place in its coarse
  * cell (the low bit of x, y, z), so a coarse cell's 8 cells are 8 consecutive buckets. Only
  * the low bits of each product matter, so each is a constant multiply of the cell's low bits
  * (two's complement: a negative coordinate's low bits times the constant's are the product's
  * low bits). With `box` (box buckets: BroadPhaseModel.BoxMap), the hash is the unit's place in
  * the padded box instead, (x - o_x) + rx (y - o_y) + rxy (z - o_z): two variable multiplies
  * of the table's width, whose low bits are all that matter. The bucket comes `latency` cycles
  * after the cell (the box map and usedLog2 are held meanwhile). */
object CellHash {
  /** Cycles from a cell to its bucket: a register after the subtractions (or the cell's low
    * bits) and one after the multiplies, so no path runs through a multiply and an add. */
  val latency = 2

  def apply(cell: Vec[SInt], bucketsLog2: Int, usedLog2: UInt, coarse: Boolean = false, box: Option[BoxMapBits] = None): UInt = {
    val w = bucketsLog2
    def hash(c: Seq[SInt], w: Int): UInt = {
      def low(c: SInt): UInt = c.pad(math.max(w, c.getWidth)).asUInt(w - 1, 0)
      box match {
        case None =>
          val lows = c.map(x => RegNext(low(x)))
          val hs = Seq(BroadPhaseModel.HashX, BroadPhaseModel.HashY, BroadPhaseModel.HashZ)
          lows.zip(hs).map { case (l, h) => RegNext((l * (h & ((1L << w) - 1)).U(w.W))(w - 1, 0)) }.reduce(_ ^ _)
        case Some(b) =>
          require(b.hashW >= w, s"a box map of ${b.hashW} bits for a hash of $w")
          val d = (0 until 3).map(a => RegNext(low(c(a) -& b.origin(a))))
          val terms = Seq(RegNext(d(0)), RegNext((b.rx(w - 1, 0) * d(1))(w - 1, 0)), RegNext((b.rxy(w - 1, 0) * d(2))(w - 1, 0)))
          (terms(0) + terms(1) + terms(2))(w - 1, 0)
      }
    }
    val h =
      if (!coarse) hash(cell, w)
      else {
        val place = ShiftRegister(Cat(cell(0)(0), cell(1)(0), cell(2)(0)), latency)
        if (w <= 3) place(w - 1, 0) else Cat(hash(cell.map(c => (c >> 1).asSInt), w - 3), place)
      }
    val mask = ((1.U((w + 1).W) << usedLog2) - 1.U)(w - 1, 0)
    h & mask
  }
}
