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
  * (min, max), chunk members in slot order, streamed spheres in order; out is valid/ready.
  * Without a hit queue (`hitQueue` 0) the stream stalls (in.ready low) while a streamed sphere
  * has more than one hit left. With one, a sphere's hits (which members, and its index) wait
  * in a queue of `hitQueue` spheres and the stream goes on: it stalls only when the queue is
  * full, so a burst of hits costs the stream nothing while the hits average under one a cycle.
  * With `drainBehind`, the members' indices (all a hit needs once it is found) are kept in two
  * banks, the chunk being loaded and the one before, and each hit owed carries its bank: a
  * clear then waits only for the hits of the chunk before the last (`canClear`), not for the
  * last chunk's, so the next chunk loads while they leave.
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
  /** A clear now loses no hit owed: `idle`, or with drainBehind no hit owed by a chunk before
    * the current one. */
  val canClear = Output(Bool())
}

class ChunkMatcher(itemW: Int, cellBits: Int, qWidth: Int, chunk: Int, hitQueue: Int = 0, drainBehind: Boolean = false,
    nearBits: Int = 0, wide: Int = 256)
    extends Module {
  require(chunk >= 1 && chunk <= 256)
  require(hitQueue >= 0 && hitQueue <= 16, s"hitQueue must be 0..16, got $hitQueue")
  require(nearBits == 0 || (nearBits >= 2 && nearBits <= qWidth), s"nearBits must be 0 (every slot wide) or 2..$qWidth, got $nearBits")
  require(wide >= 0, s"wide must be >= 0, got $wide")
  /** Slots with the whole box filter: every slot without near ones. */
  private val wideSlots = if (nearBits == 0) chunk else math.min(wide, chunk)
  override def desiredName = s"ChunkMatcher_i${itemW}_c${cellBits}_q${qWidth}_k$chunk" + (if (hitQueue > 0) s"_h$hitQueue" else "") +
    (if (drainBehind) "_d" else "") + (if (nearBits > 0) s"_n${nearBits}w$wideSlots" else "")
  private val key = new WorldKey(itemW, cellBits, qWidth)
  val io = IO(new ChunkMatcherIO(key, chunk))

  private val members = Reg(Vec(chunk, new ChunkMember(itemW, cellBits, qWidth)))
  // Each member's box, q -+ qr on each axis, kept as it loads: the filter then compares it with
  // the probe's box widened by the slack (two comparisons an axis) instead of computing
  // |qa - qb| and qa.r + qb.r + slack for every member (a subtraction, a negation, a
  // multiplexer and two additions more). The same test exactly: qa - qra <= qb + qrb + slack
  // and qb - qrb - slack <= qa + qra together say |qa - qb| <= qra + qrb + slack.
  // With near slots (nearBits > 0), the slots from `wide` on keep their box modulo 2^nearBits
  // only: they hold a chunk of the grid, whose probes are in cells next to the members', where
  // the filter's differences are below 2^(nearBits-1) (ChunkMatcher.nearBits), so a difference's
  // sign modulo 2^nearBits is its true sign. The large pass, whose probes may be anywhere, loads
  // the wide slots only.
  private val wideBoxes = Reg(Vec(wideSlots, new ChunkMatcher.Box(qWidth + 2)))
  private val nearBoxes = Reg(Vec(chunk - wideSlots, new ChunkMatcher.NearBox(nearBits max 1)))
  private def writeBox(slot: UInt, k: WorldKey): Unit = {
    val w = ChunkMatcher.box(k, None)
    val n = ChunkMatcher.nearBox(k, None, nearBits max 1)
    for (m <- 0 until chunk) when(slot === m.U) { if (m < wideSlots) wideBoxes(m) := w else nearBoxes(m - wideSlots) := n }
  }
  private val used = RegInit(0.U(log2Ceil(chunk + 1).W))
  private val over = RegInit(false.B)
  io.overflow := over
  // A clear and a load in one cycle start the new chunk with that member.
  // With drainBehind: the members' indices by bank; `cur` is the bank being loaded (a clear
  // switches), and the other one is the chunk before, whose hits may still be owed.
  private val cur = RegInit(false.B)
  // Two registers, not a Vec of two: a bank chosen at run time would be a mux of arrays, which
  // the Verilog we emit for Yosys may not have (docs/conventions.md, "Tools").
  private val ids = Seq.fill(2)(Reg(Vec(chunk, UInt(itemW.W))))
  private def writeId(bank: Bool, m: UInt, index: UInt): Unit =
    for (b <- 0 until 2) when(bank === (b == 1).B) { ids(b)(VecIndex(m, chunk)) := index }
  when(io.clear) {
    used := io.load.valid.asUInt; over := false.B
    when(io.load.valid) { members(0) := io.load.bits; writeBox(0.U, io.load.bits.key) }
    if (drainBehind) {
      cur := !cur
      when(io.load.valid) { writeId(!cur, 0.U, io.load.bits.key.index) }
    }
  }.elsewhen(io.load.valid) {
    when(used === chunk.U) { over := true.B }
      .otherwise {
        members(VecIndex(used, chunk)) := io.load.bits; writeBox(used, io.load.bits.key); used := used + 1.U
        if (drainBehind) writeId(cur, used, io.load.bits.key.index)
      }
  }
  /** Member m's index: its bank's with drainBehind (the members' own are then not read). */
  private def memberIndex(bank: Bool, m: UInt): UInt =
    if (drainBehind) Mux(bank, ids(1)(VecIndex(m, chunk)), ids(0)(VecIndex(m, chunk))) else members(VecIndex(m, chunk)).key.index

  /** The box filter of member box `a` and the probe's box `b` (widened by the slack). */
  private def boxTests(a: ChunkMatcher.Box, b: ChunkMatcher.Box): Seq[Bool] =
    (0 until 3).flatMap(ax => Seq(a.lo(ax) <= b.hi(ax), b.lo(ax) <= a.hi(ax)))

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

  // With a hit queue, a probe is compared the cycle after it is taken: the probe, its box
  // widened by the slack and the members loaded so far are registered (`st*`), so neither
  // path, the box's additions from the streamed entry nor the compares into the hit queue,
  // follows the other in one cycle. The members compared are the first `stUsed`, those loaded
  // before the probe was taken: a load in its cycle (a coarse chunk's scan pairs) writes a
  // later slot, and nothing clears in that cycle (a clear comes with a scan entry or an idle
  // stream, never with a probe). Without a queue the comparison stays in the taking cycle.
  private val staged = hitQueue > 0
  private val inBox = ChunkMatcher.box(io.in.bits.key, Some(io.slack))
  private val inNear = ChunkMatcher.nearBox(io.in.bits.key, Some(io.slack), nearBits max 1)
  private val stV = RegInit(false.B)
  private val stProbe = Reg(chiselTypeOf(io.in.bits))
  private val stBox = Reg(chiselTypeOf(inBox))
  private val stNear = Reg(chiselTypeOf(inNear))
  private val stUsed = Reg(chiselTypeOf(used))
  if (staged) {
    stV := io.in.fire
    when(io.in.fire) { stProbe := io.in.bits; stBox := inBox; stNear := inNear; stUsed := used }
    assert(!(io.in.fire && io.clear), "ChunkMatcher: a probe taken in a clear's cycle")
  }
  private val probe = if (staged) stProbe else io.in.bits
  private val e = probe.key
  private val probeBox = if (staged) stBox else inBox
  private val probeNear = if (staged) stNear else inNear
  private val usedAt = if (staged) stUsed else used
  /** The near filter: hi_p - lo_m >= 0 and hi_m - lo_p >= 0 by their signs modulo 2^nearBits. */
  private def nearTests(a: ChunkMatcher.NearBox, b: ChunkMatcher.NearBox): Seq[Bool] =
    (0 until 3).flatMap(ax => Seq(!(b.hi(ax) -% a.lo(ax))(nearBits - 1), !(a.hi(ax) -% b.lo(ax))(nearBits - 1)))
  private val inCell = e.cell.zip(probe.cell).map { case (a, b) => a === b }.reduce(_ && _)
  /** Which members come before the probe: a hit's order (i < j) is known when it is found.
    * With a hit queue, compared when the probe is taken and registered with it: the members it
    * is compared with (those before stUsed) and the bank are the same then (a take's own load
    * writes a later slot, and no clear comes with a take), and the index compare's carry chain
    * then does not lead the box filter's into the hits. */
  private val inLater = VecInit((0 until chunk).map(m => io.in.bits.key.index > memberIndex(cur, m.U))).asUInt
  private val stLater = Reg(UInt(chunk.W))
  if (staged) when(io.in.fire) { stLater := inLater }
  private val laterNow = if (staged) stLater else inLater
  /** Each member's six box-filter tests (two an axis), and whether its other conditions hold:
    * loaded before the probe, and the cell rules. A hit needs all seven. */
  private val boxNow = VecInit((0 until chunk).map { m =>
    VecInit(if (m < wideSlots) boxTests(wideBoxes(m), probeBox) else nearTests(nearBoxes(m - wideSlots), probeNear)).asUInt
  })
  private val gateNow = VecInit((0 until chunk).map { m =>
    val later = laterNow(m)
    val takes = Mux(probe.anyCell, !probe.own || later, inCell && owns(members(m).place, probe.off, later))
    m.U < usedAt && takes
  }).asUInt
  private def hitsOf(box: Vec[UInt], gate: UInt): UInt = VecInit((0 until chunk).map(m => gate(m) && box(m).andR)).asUInt
  private val hitsNow = hitsOf(boxNow, gateNow)

  // The streamed sphere being drained (its index) and the hits it still owes.
  private val pending = RegInit(0.U(chunk.W))
  private val entry = Reg(UInt(itemW.W))
  private val pendBank = Reg(Bool()) // the bank of the members `pending` names
  // Which of them come before `entry` (laterNow, registered with the hits), so the pair's
  // order needs no compare after the slot is found.
  private val pendLater = Reg(UInt(chunk.W))
  private val slot = PriorityEncoder(pending)
  private val lastHit = PopCount(pending) <= 1.U
  io.out.valid := pending.orR
  private val mIndex = memberIndex(pendBank, slot)
  private val memberFirst = pendLater(slot)
  io.out.bits.i := Mux(memberFirst, mIndex, entry)
  io.out.bits.j := Mux(memberFirst, entry, mIndex)
  // Hits are owed in order, the chunk before's first: none of it is left once neither the
  // sphere draining nor the queue's head is of the other bank.
  private val pendOld = pending.orR && pendBank =/= cur
  private val oldQueued = Wire(Bool()) // the queue's head is a hit of the chunk before (none without a queue)
  private val drained = Mux(io.out.fire, pending & ~UIntToOH(slot, chunk), pending)
  // The drain takes its next sphere when it has nothing left to owe after this cycle.
  private val free = !pending.orR || (lastHit && io.out.ready)
  if (hitQueue == 0) {
    io.in.ready := free
    pending := Mux(io.in.fire, hitsNow, drained)
    when(io.in.fire) { entry := e.index; pendBank := cur; pendLater := laterNow }
    io.idle := !pending.orR
    oldQueued := false.B
  } else {
    // Only spheres with a hit are queued; the comparators' result never reaches in.ready
    // (a long path), so a full queue stops the stream even for a sphere without one.
    class Hits extends Bundle { val mask = UInt(chunk.W); val later = UInt(chunk.W); val index = UInt(itemW.W); val bank = Bool() }
    // The compare's result is registered (`found`) before it is queued, so no path runs from
    // the boxes' compares through the queue's count. Two more entries, for the probe being
    // compared and the one found: a probe is taken only while the queue has room for it after
    // those before, so `hitQueue` spheres' hits still wait as without the stages.
    val q = Module(new Queue(new Hits, hitQueue + 2))
    val foundV = RegNext(stV, false.B)
    // The tests are registered before they are combined: the box filter's compares (carry
    // chains) and the AND of a member's seven conditions then take a cycle each.
    val foundBox = Reg(chiselTypeOf(boxNow))
    val foundGate = Reg(UInt(chunk.W))
    val foundRest = Reg(new Hits) // its mask is foundBox and foundGate's
    when(stV) { foundBox := boxNow; foundGate := gateNow; foundRest.later := laterNow; foundRest.index := e.index; foundRest.bank := cur }
    val found = WireDefault(foundRest)
    found.mask := hitsOf(foundBox, foundGate)
    // The queue's count, mirrored in a register of our own: the Queue's (a difference of its
    // pointers, not a power of two) was a long path into in.ready.
    val held = RegInit(0.U(log2Ceil(hitQueue + 3).W))
    held := held + q.io.enq.fire.asUInt - q.io.deq.fire.asUInt
    io.in.ready := (held +& stV.asUInt +& foundV.asUInt) <= (hitQueue + 1).U
    q.io.enq.valid := foundV && found.mask.orR
    q.io.enq.bits := found
    q.io.deq.ready := free
    pending := Mux(q.io.deq.fire, q.io.deq.bits.mask, drained)
    when(q.io.deq.fire) { entry := q.io.deq.bits.index; pendBank := q.io.deq.bits.bank; pendLater := q.io.deq.bits.later }
    io.idle := !pending.orR && !q.io.deq.valid && !stV && !foundV
    // Hits of the chunk before still owed: at the queue's head, or found and not yet queued.
    // (A found probe of the chunk before holds a clear back for its cycle, hits or none.)
    oldQueued := (q.io.deq.valid && q.io.deq.bits.bank =/= cur) || (foundV && found.bank =/= cur)
  }
  io.canClear := (if (drainBehind) !pendOld && !oldQueued else io.idle)
}

object ChunkMatcher {
  /** A sphere's box on the box filter's fixed point: lo = q - r and hi = q + r on each axis. */
  class Box(w: Int) extends Bundle {
    val lo = Vec(3, SInt(w.W))
    val hi = Vec(3, SInt(w.W))
  }
  /** A box modulo 2^w (near slots): lo = q - r and hi = q + r, their low w bits. */
  class NearBox(w: Int) extends Bundle {
    val lo = Vec(3, UInt(w.W))
    val hi = Vec(3, UInt(w.W))
  }
  def nearBox(k: WorldKey, grow: Option[UInt], w: Int): NearBox = {
    val r = grow.fold(k.qr)(g => k.qr +& g)(w - 1, 0)
    val b = Wire(new NearBox(w))
    for (ax <- 0 until 3) { val q = k.q(ax).asUInt(w - 1, 0); b.lo(ax) := q -% r; b.hi(ax) := q +% r }
    b
  }
  /** Near bits that make the near filter exact in the grid (a probe in a cell next to the
    * members'; every small sphere's qr at most half a cell, E / 2 <= 2^(F-1); the slack at
    * most 1 + 2^(F - cellOverError)): member and probe cells differ by at most 2 on an axis
    * (a member's place 0..1 in its coarse cell, a visit's offset -1..2), so |qa - qb| < 3E,
    * and hi_p - lo_m = qb - qa + qra + qrb + slack lies within (-3E, 4E + slack] with E <=
    * 2^F (the edge in filter units): below 2^(F+3) in magnitude. */
  def nearBits(filterFracBits: Int): Int = filterFracBits + 4

  /** Key k's box, widened by `grow` (the probe's slack) when given, in `w` bits: exact, as q
    * and r below 2^(qWidth-1) and 2^qWidth need qWidth + 2 bits for a member's box and
    * qWidth + 3 with a slack below 2^qWidth. */
  def box(k: WorldKey, grow: Option[UInt]): Box = {
    val w = k.qWidth + (if (grow.isDefined) 3 else 2)
    val r = grow.fold(k.qr.zext)(g => (k.qr +& g).zext)
    val b = Wire(new Box(w))
    for (ax <- 0 until 3) { b.lo(ax) := (k.q(ax) -& r).pad(w)(w - 1, 0).asSInt; b.hi(ax) := (k.q(ax) +& r).pad(w)(w - 1, 0).asSInt }
    b
  }
}
