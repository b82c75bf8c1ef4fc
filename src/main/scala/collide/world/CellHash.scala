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
  * low bits). With `box` (box buckets: BroadPhaseModel.boxBits, bits B_x, B_y, B_z), the hash
  * is x mod 2^B_x + (y mod 2^B_y) 2^B_x + (z mod 2^B_z) 2^(B_x + B_y) instead: masks and shifts. */
object CellHash {
  def apply(cell: Vec[SInt], bucketsLog2: Int, usedLog2: UInt, coarse: Boolean = false, box: Option[Vec[UInt]] = None): UInt = {
    val w = bucketsLog2
    def hash(c: Seq[SInt], w: Int): UInt = {
      def low(c: SInt): UInt = c.pad(math.max(w, c.getWidth)).asUInt(w - 1, 0)
      def times(c: SInt, h: Long): UInt = (low(c) * (h & ((1L << w) - 1)).U(w.W))(w - 1, 0)
      box match {
        case None => times(c(0), BroadPhaseModel.HashX) ^ times(c(1), BroadPhaseModel.HashY) ^ times(c(2), BroadPhaseModel.HashZ)
        case Some(b) =>
          def masked(c: SInt, n: UInt): UInt = low(c) & ((1.U((w + 1).W) << n) - 1.U)(w - 1, 0)
          (masked(c(0), b(0)) | (masked(c(1), b(1)) << b(0)) | (masked(c(2), b(2)) << (b(0) +& b(1))))(w - 1, 0)
      }
    }
    val h =
      if (!coarse) hash(cell, w)
      else {
        val place = Cat(cell(0)(0), cell(1)(0), cell(2)(0))
        if (w <= 3) place(w - 1, 0) else Cat(hash(cell.map(c => (c >> 1).asSInt), w - 3), place)
      }
    val mask = ((1.U((w + 1).W) << usedLog2) - 1.U)(w - 1, 0)
    h & mask
  }
}
