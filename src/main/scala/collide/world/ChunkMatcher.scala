package collide.world

import chisel3._
import chisel3.util._

/** The heart of the cell-major candidate generator (docs/afu.md, "World mode"): holds a
  * chunk of up to `chunk` spheres (of one cell, or of one coarse cell of 2 x 2 x 2 cells) and
  * compares each sphere streamed past (the entries of a visited bucket, each a WorldProbe)
  * with all of them in one cycle: the probe must be in its visited cell; a member takes it
  * if the visited cell is the member's own and the probe has the larger index, or lies in the
  * member's half shell (the visit's offset from the chunk's base less the member's place,
  * BroadPhaseModel.owns); and the exact box filter |qa - qb| <= qra + qrb + slack must pass
  * on every axis. The large pass's probes (anyCell) skip the cell rules. Visits may follow
  * each other back to back (the visit travels with each probe). Hits leave one pair a cycle,
  * (min, max), chunk members in slot order; the stream stalls (in.ready low) while a streamed
  * sphere has more than one hit left, and out is valid/ready.
  */
class ChunkMatcherIO(p: WorldKey, chunk: Int) extends Bundle {
  /** Empties the chunk (between chunks); with a load in the same cycle, that is the first member. */
  val clear = Input(Bool())
  /** Adds a member to the chunk (at most `chunk` after a clear; more is refused: overflow). */
  val load = Flipped(Valid(new ChunkMember(p.itemW, p.cellBits, p.qWidth)))
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

  private val members = Reg(Vec(chunk, new ChunkMember(itemW, cellBits, qWidth)))
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

  /** The half-shell rule of a member at `place` for a probe of the visit at `off` (both from
    * the chunk's base cell): the member's own cell needs the larger index (`later`); else the
    * offset between their cells (-2..2 an axis) must be one of the 13 half-shell offsets. */
  private def owns(place: UInt, off: Vec[SInt], later: Bool): Bool = {
    val rel = (0 until 3).map(a => off(a) -& place(2 - a).zext)
    val zero = rel.map(_ === 0.S)
    val one = rel.map(_ === 1.S)
    val near = rel.map(r => r >= -1.S && r <= 1.S)
    val half = (one(0) && near(1) && near(2)) || (zero(0) && one(1) && near(2)) || (zero(0) && zero(1) && one(2))
    Mux(zero.reduce(_ && _), later, half)
  }

  private val probe = io.in.bits
  private val e = probe.key
  private val inCell = e.cell.zip(probe.cell).map { case (a, b) => a === b }.reduce(_ && _)
  private val hitsNow = VecInit((0 until chunk).map { m =>
    val mem = members(m)
    val later = e.index > mem.key.index
    val takes = Mux(probe.anyCell, !probe.own || later, inCell && owns(mem.place, probe.off, later))
    m.U < used && takes && boxPass(mem.key, e)
  }).asUInt

  // The entry being drained and the hits it still owes.
  private val pending = RegInit(0.U(chunk.W))
  private val entry = Reg(key)
  private val slot = PriorityEncoder(pending)
  private val lastHit = PopCount(pending) <= 1.U
  io.out.valid := pending.orR
  private val m = members(VecIndex(slot, chunk)).key
  io.out.bits.i := Mux(m.index < entry.index, m.index, entry.index)
  io.out.bits.j := Mux(m.index < entry.index, entry.index, m.index)
  io.in.ready := !pending.orR || (lastHit && io.out.ready)
  private val drained = Mux(io.out.fire, pending & ~UIntToOH(slot, chunk), pending)
  pending := Mux(io.in.fire, hitsNow, drained)
  when(io.in.fire) { entry := e }
  io.idle := !pending.orR
}
