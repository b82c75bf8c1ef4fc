package collide.afu

import chisel3._
import chisel3.util._

/** Sends contact lines, then (when asked) the status line, with at most `maxWrites` writes in
  * flight (one tag each). Write responses come back in any order and free their tag. */
class WriteEngine(p: PucParams) extends Module {
  override def desiredName = s"WriteEngine_w${p.maxWrites}${p.name}"
  val io = IO(new Bundle {
    val lines       = Flipped(Decoupled(new LineWrite))
    val status      = Flipped(Decoupled(new LineWrite))
    val wrReq       = Decoupled(new WrReq(p.tagBits))
    val wrResp      = Flipped(Valid(new WrResp(p.tagBits)))
    val outstanding = Output(UInt(log2Ceil(p.maxWrites + 1).W))
    val blocked     = Output(Bool())   // a line waits on back-pressure or on a free tag
  })
  val tags = Module(new TagPool(p.maxWrites, p.tagBits, p.name + "_wr"))
  val useStatus = !io.lines.valid && io.status.valid
  val any = io.lines.valid || io.status.valid
  io.wrReq.valid     := any && tags.io.alloc.valid
  io.wrReq.bits.tag  := tags.io.alloc.bits
  io.wrReq.bits.addr := Mux(useStatus, io.status.bits.addr, io.lines.bits.addr)
  io.wrReq.bits.data := Mux(useStatus, io.status.bits.data, io.lines.bits.data)
  tags.io.alloc.ready := io.wrReq.ready && any
  io.lines.ready  := io.wrReq.ready && tags.io.alloc.valid
  io.status.ready := io.wrReq.ready && tags.io.alloc.valid && !io.lines.valid
  tags.io.free.valid := io.wrResp.valid
  tags.io.free.bits  := io.wrResp.bits.tag
  io.outstanding := tags.io.inUse
  io.blocked := any && !io.wrReq.fire
}
