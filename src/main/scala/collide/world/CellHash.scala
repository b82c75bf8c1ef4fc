package collide.world

import chisel3._
import chisel3.util._
import collide.world.model.BroadPhaseModel

/** The bucket of a cell, as BroadPhaseModel.bucket: ((cx * HashX) ^ (cy * HashY) ^
  * (cz * HashZ)) mod the used buckets. Only the low bucketsLog2 bits of each product matter,
  * so each is a bucketsLog2-bit constant multiply of the cell's low bits (two's complement:
  * a negative coordinate's low bits times the constant's are the product's low bits). */
object CellHash {
  def apply(cell: Vec[SInt], bucketsLog2: Int, usedLog2: UInt): UInt = {
    val w = bucketsLog2
    def low(c: SInt): UInt = c.pad(math.max(w, c.getWidth)).asUInt(w - 1, 0)
    def times(c: SInt, h: Long): UInt = (low(c) * (h & ((1L << w) - 1)).U(w.W))(w - 1, 0)
    val h = times(cell(0), BroadPhaseModel.HashX) ^ times(cell(1), BroadPhaseModel.HashY) ^ times(cell(2), BroadPhaseModel.HashZ)
    val mask = ((1.U((w + 1).W) << usedLog2) - 1.U)(w - 1, 0)
    h & mask
  }
}
