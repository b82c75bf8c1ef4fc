package collide.afu

import chisel3._
import chisel3.util._

/** Free-tag bitmap: hands out the lowest free tag, takes tags back from responses. Its size
  * is the request limit, so "a tag is free" is "another request may be in flight". */
class TagPool(n: Int, tagBits: Int, suffix: String) extends Module {
  override def desiredName = s"TagPool_n${n}$suffix"
  val io = IO(new Bundle {
    val alloc = Decoupled(UInt(tagBits.W))
    val free  = Flipped(Valid(UInt(tagBits.W)))
    val inUse = Output(UInt(log2Ceil(n + 1).W))
  })
  val freeMap = RegInit(VecInit(Seq.fill(n)(true.B)))
  val count   = RegInit(0.U(log2Ceil(n + 1).W))
  io.alloc.valid := freeMap.asUInt.orR
  io.alloc.bits  := PriorityEncoder(freeMap.asUInt)
  val take = io.alloc.fire
  val give = io.free.valid
  when(take) { freeMap(io.alloc.bits) := false.B }
  when(give) { freeMap(io.free.bits(log2Ceil(n) - 1, 0)) := true.B }
  count := count + take.asUInt - give.asUInt
  io.inUse := count
  assert(!give || !freeMap(io.free.bits(log2Ceil(n) - 1, 0)), "TagPool: a response came back for a tag not in flight")
}
