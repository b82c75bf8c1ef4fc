package collide.formal

import chisel3._
import chisel3.util._
import collide.afu._

/** TagPool with a taker that takes when it likes and responses that free only tags in flight
  * (the wrapper's own set of them), one a cycle. Proven: a tag handed out is below n and not
  * in flight; a tag is offered whenever fewer than n are in flight; inUse is the number in
  * flight; and the pool's own assertion (no response for a tag not in flight).
  * SeededBug: the wrapper forgets a take of tag 0 (a dropped valid), so inUse disagrees. */
class TagPoolFormal(n: Int, tagBits: Int, check: Check = Check.Prove) extends Module {
  val io = IO(new Bundle {
    val take = Input(Bool())
    val free = Flipped(Valid(UInt(tagBits.W)))
  })
  val dut = Module(new TagPool(n, tagBits, "_formal"))
  dut.io.alloc.ready := io.take
  dut.io.free := io.free
  // The wrapper's set of tags in flight.
  val inFlight = RegInit(0.U(n.W))
  private val seen = if (check == Check.SeededBug) dut.io.alloc.fire && dut.io.alloc.bits =/= 0.U else dut.io.alloc.fire
  private val takeOH = Mux(seen, UIntToOH(dut.io.alloc.bits(log2Ceil(n) - 1, 0), n), 0.U)
  private val freeOH = Mux(io.free.valid, UIntToOH(io.free.bits(log2Ceil(n) - 1, 0), n), 0.U)
  inFlight := (inFlight | takeOH) & ~freeOH
  when(io.free.valid) { assume(io.free.bits < n.U && inFlight(io.free.bits(log2Ceil(n) - 1, 0)), "a response frees a tag in flight") }

  when(dut.io.alloc.valid) {
    assert(dut.io.alloc.bits < n.U, "a tag handed out is below n")
    assert(!inFlight(dut.io.alloc.bits(log2Ceil(n) - 1, 0)), "a tag handed out is not in flight")
  }
  assert(dut.io.alloc.valid === (PopCount(inFlight) < n.U), "a tag is offered while one is free")
  assert(dut.io.inUse === PopCount(inFlight), "inUse counts the tags in flight")
  // Finish: every tag was in flight at once, and all have come back.
  private val wasFull = RegInit(false.B)
  when(inFlight.andR) { wasFull := true.B }
  FormalEnv.finish(check, wasFull && inFlight === 0.U, "every tag in flight at once, then all back")
}
