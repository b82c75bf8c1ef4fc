package collide.world

import chisel3._
import chisel3.util._

/** The heart of the cell-major candidate generator (docs/afu.md, "World mode"): holds a
  * chunk of up to `chunk` spheres of one cell and compares each sphere streamed past (the
  * entries of a visited bucket, each a WorldProbe) with all of them in one cycle: in the
  * probe's visited cell, j > i if the probe says own, and the exact box filter
  * |qa - qb| <= qra + qrb + slack on every axis. Visits may follow each other back to back
  * (the visit travels with each probe). Hits
  * leave one pair a cycle, (min, max), chunk members in slot order; the stream stalls
  * (in.ready low) while a streamed sphere has more than one hit left, and out is valid/ready.
  */
class ChunkMatcherIO(p: WorldKey, chunk: Int) extends Bundle {
  /** Empties the chunk (between cells); with a load in the same cycle, that is the first member. */
  val clear = Input(Bool())
  /** Adds a member to the chunk (at most `chunk` after a clear; more is refused: overflow). */
  val load = Flipped(Valid(p.cloneType))
  val overflow = Output(Bool())
  /** The box filter's slack at this world's k. */
  val slack = Input(UInt(p.qWidth.W))
  val in = Flipped(Decoupled(new WorldProbe(p.itemW, p.cellBits, p.qWidth)))
  val out = Decoupled(new WorldPair(p.itemW))
  /** Nothing in flight: every hit of the accepted entries has left. */
  val idle = Output(Bool())
}

class ChunkMatcher(itemW: Int, cellBits: Int, qWidth: Int, chunk: Int) extends Module {
  require(chunk >= 1 && chunk <= 256)
  override def desiredName = s"ChunkMatcher_i${itemW}_c${cellBits}_q${qWidth}_k$chunk"
  private val key = new WorldKey(itemW, cellBits, qWidth)
  val io = IO(new ChunkMatcherIO(key, chunk))

  private val members = Reg(Vec(chunk, key))
  private val used = RegInit(0.U(log2Ceil(chunk + 1).W))
  private val over = RegInit(false.B)
  io.overflow := over
  // A clear and a load in one cycle start the new chunk with that member.
  when(io.clear) {
    used := io.load.valid.asUInt; over := false.B
    when(io.load.valid) { members(0) := io.load.bits }
  }.elsewhen(io.load.valid) {
    when(used === chunk.U) { over := true.B }
      .otherwise { members(VecIndex(used, chunk)) := io.load.bits; used := used + 1.U }
  }

  private def boxPass(a: WorldKey, b: WorldKey): Bool = {
    val bound = a.qr +& b.qr +& io.slack
    (0 until 3).map { ax =>
      val d = a.q(ax) -& b.q(ax)
      Mux(d < 0.S, (0.S -& d).asUInt, d.asUInt) <= bound
    }.reduce(_ && _)
  }

  private val probe = io.in.bits
  private val e = probe.key
  private val inCell = probe.anyCell || e.cell.zip(probe.cell).map { case (a, b) => a === b }.reduce(_ && _)
  private val hitsNow = VecInit((0 until chunk).map { m =>
    m.U < used && inCell && (!probe.own || e.index > members(m).index) && boxPass(members(m), e)
  }).asUInt

  // The entry being drained and the hits it still owes.
  private val pending = RegInit(0.U(chunk.W))
  private val entry = Reg(key)
  private val slot = PriorityEncoder(pending)
  private val lastHit = PopCount(pending) <= 1.U
  io.out.valid := pending.orR
  private val m = members(VecIndex(slot, chunk))
  io.out.bits.i := Mux(m.index < entry.index, m.index, entry.index)
  io.out.bits.j := Mux(m.index < entry.index, entry.index, m.index)
  io.in.ready := !pending.orR || (lastHit && io.out.ready)
  private val drained = Mux(io.out.fire, pending & ~UIntToOH(slot, chunk), pending)
  pending := Mux(io.in.fire, hitsNow, drained)
  when(io.in.fire) { entry := e }
  io.idle := !pending.orR
}
