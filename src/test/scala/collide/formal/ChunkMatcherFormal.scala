package collide.formal

import chisel3._
import chisel3.util._
import collide.world._

/** ChunkMatcher with a hit queue (`hitQueue` spheres) beside the same matcher without one (a
  * miter): the queue lets the stream go on while a sphere's hits leave, and must change only
  * when the pairs leave, never which pairs or their order. Both get the same clears, loads and
  * slack; the queued one takes probes from the environment (any bits, any valid), and each
  * probe it accepts goes on, through a FIFO, to the plain one. Each matcher's pairs go into a
  * FIFO of their own; while both hold one, the heads are compared and dropped. The environment
  * clears and loads only while both are idle and no probe waits for the plain one, and holds
  * the slack from reset; the pairs' consumer is ready or not at will.
  *
  * Proven: the heads agree (same pair, same order); the two overflow alike; and whenever both
  * are idle with no probe between them, the two have put out the same number of pairs (none
  * lost or added by the queue). SeededBug: the wrapper drops the queued matcher's pairs whose
  * smaller index is 0 (a dropped valid). */
class ChunkMatcherFormal(itemW: Int = 3, cellBits: Int = 2, qWidth: Int = 4, chunk: Int = 2, hitQueue: Int = 2,
    check: Check = Check.Prove) extends Module {
  val io = IO(new Bundle {
    val clear = Input(Bool())
    val load  = Flipped(Valid(new ChunkMember(itemW, cellBits, qWidth)))
    val slack = Input(UInt(qWidth.W))
    val probe = Flipped(Decoupled(new WorldProbe(itemW, cellBits, qWidth)))
    val ready = Input(Bool())
  })
  val queued = Module(new ChunkMatcher(itemW, cellBits, qWidth, chunk, hitQueue = hitQueue))
  val plain  = Module(new ChunkMatcher(itemW, cellBits, qWidth, chunk))
  private val between = Module(new Queue(new WorldProbe(itemW, cellBits, qWidth), 4))
  private val outQ = Module(new Queue(new WorldPair(itemW), 4))
  private val outP = Module(new Queue(new WorldPair(itemW), 4))

  for (m <- Seq(queued, plain)) { m.io.clear := io.clear; m.io.load := io.load; m.io.slack := io.slack }
  queued.io.in.valid := io.probe.valid && between.io.enq.ready
  queued.io.in.bits := io.probe.bits
  io.probe.ready := queued.io.in.ready && between.io.enq.ready
  between.io.enq.valid := queued.io.in.fire
  between.io.enq.bits := io.probe.bits
  plain.io.in <> between.io.deq

  // Each matcher's pairs into its FIFO (SeededBug: the queued one's pairs with i = 0 dropped).
  private val dropped = if (check == Check.SeededBug) queued.io.out.bits.i === 0.U else false.B
  outQ.io.enq.valid := queued.io.out.valid && !dropped && io.ready
  outQ.io.enq.bits := queued.io.out.bits
  queued.io.out.ready := outQ.io.enq.ready && io.ready || dropped
  outP.io.enq <> plain.io.out
  private val both = outQ.io.deq.valid && outP.io.deq.valid
  outQ.io.deq.ready := both
  outP.io.deq.ready := both

  // ---- the environment
  FormalEnv.stable(io.slack)
  private val quiet = queued.io.idle && plain.io.idle && !between.io.deq.valid
  when(io.clear || io.load.valid) { assume(quiet && !io.probe.valid, "clear and load only between streams") }

  // ---- the checks
  when(both) {
    assert(outQ.io.deq.bits.asUInt === outP.io.deq.bits.asUInt, "the queued matcher's k-th pair is the plain one's")
  }
  assert(queued.io.overflow === plain.io.overflow, "the two overflow alike")
  private val compared = FormalEnv.counter(both.asUInt, 4)
  when(quiet) { assert(outQ.io.count === outP.io.count, "idle: the two have put out as many pairs") }
  FormalEnv.finish(check, quiet && compared >= 2.U && outQ.io.count === 0.U && outP.io.count === 0.U,
    "two pairs compared, both matchers idle and their FIFOs empty")
}
