package collide.afu

import chisel3._
import chisel3.util._
import collide.util.Prefix
import collide.world.WorldPair

/** World mode: packs the broad phase's candidate pairs, one a cycle from each of its `lanes`,
  * into pair lines for the dispatcher, exactly as the host lays out a pair list (u16 i, u16 j;
  * pair k of line l is candidate 16 l + k; the lanes' pairs of one cycle in lane order). A
  * line leaves when full, or part-full once `done` says no candidate will follow. `emitted`
  * counts the candidates in lines handed out; the dispatcher takes it as the run's pair count,
  * so a line's pairs are min(16, emitted - its first), which is the line's own count (a
  * part-full line is the last). Unused slots are zero. Up to `queue` lines wait for the
  * dispatcher (2 by default): a deeper queue lets the lanes run on while a burst of contacts
  * holds the SCPUs' results at the collector (docs/afu.md, "Starting ahead").
  *
  * The lanes' pairs go through three steps so that no path counts the lanes and places their
  * pairs in one cycle (that path was 11 ns of cells, and a prefix count of 16 lanes in one
  * cycle is still 13 ns: carry chains in series): each valid pair's rank among the lanes' is
  * a prefix count, one Kogge-Stone level a cycle; the pairs are then compacted in lane order;
  * then appended to a buffer of `cap` slots, from which the first line leaves. The steps move
  * together, every lane ready together, from registers only: unless the compacted pairs wait
  * for the buffer's room. A pair takes 1 + log2(lanes) cycles more than in one step.
  */
class WorldPairLines(p: PucParams, itemW: Int, lanes: Int = 1, queue: Int = 2) extends Module {
  override def desiredName = s"WorldPairLines_i${itemW}" + (if (lanes > 1) s"_l$lanes" else "") +
    (if (queue != 2) s"_q$queue" else "") + p.name
  private val ppl = p.layout.pairsPerLine
  require(lanes >= 1 && lanes <= 2 * ppl, s"WorldPairLines: lanes must be 1..${2 * ppl} (two lines' pairs), got $lanes")
  require(queue >= 2 && queue <= 4096, s"WorldPairLines: queue must be 2..4096 lines, got $queue")
  val io = IO(new Bundle {
    val start   = Input(Bool()) // a new run: counters to zero (nothing may be held)
    val in      = Vec(lanes, Flipped(Decoupled(new WorldPair(itemW))))
    val done    = Input(Bool())
    val out     = Decoupled(new PairLine(p.pairLineBits))
    val emitted = Output(UInt((p.layout.pairIndexBits + 1).W))
    val idle    = Output(Bool()) // nothing held, nothing waiting to leave
  })

  // The buffer: a line, and room behind it for a whole step of pairs with less than a line
  // before them (a power of two, so a leaving line's place is a subtraction of a top bit).
  private val cap = ppl * (if (lanes <= ppl) 2 else 4)
  private val cntW = log2Ceil(cap)
  private val rankW = log2Ceil(lanes + 1)
  private val rankLevels = math.max(1, Prefix.levelCount(lanes))
  private def pack(pr: WorldPair): UInt = Cat(pr.j.pad(16), pr.i.pad(16))

  // Step 2: the pairs compacted, in lane order: the j-th is there when bHas(j).
  private val bAny  = RegInit(false.B)
  private val bHas  = Reg(Vec(lanes, Bool()))
  private val bData = Reg(Vec(lanes, UInt(32.W)))
  private val bCount = Reg(UInt(rankW.W))
  // Step 3: the buffer; slots [0, cnt) hold pairs, the first line in slots [0, ppl).
  private val slots   = Reg(Vec(cap, UInt(32.W)))
  private val cnt     = RegInit(0.U(cntW.W))
  private val line    = RegInit(0.U(p.pairLineBits.W))
  private val emitted = RegInit(0.U((p.layout.pairIndexBits + 1).W))
  private val q = Module(new Queue(new PairLine(p.pairLineBits), queue) {
    override def desiredName = "WorldLineQueue" + (if (queue != 2) s"_d$queue" else "") + p.name
  })

  // Step 1: the ranks' levels, the pairs and their valid bits moving beside them. Every level
  // moves when the last can hand on its pairs (`adv`); bubbles are not squeezed out.
  private val adv = Wire(Bool())
  private val valids = io.in.map(_.valid)
  private def held[T <: Data](x: T): T = RegEnable(x, adv)
  private val sums0 = Prefix.levels(valids.map(v => Mux(v, 1.U(rankW.W), 0.U(rankW.W))), (lv: Seq[UInt]) => lv.map(held(_)))(_ + _)
  private val sums = if (Prefix.levelCount(lanes) == 0) sums0.map(held(_)) else sums0 // one lane: a register still
  private val anys = Seq.iterate(io.in.map(_.valid).reduce(_ || _), rankLevels + 1)(x => RegEnable(x, false.B, adv)).tail
  private val aAny = anys.last
  private val aValid = valids.map(ShiftRegister(_, rankLevels, adv))
  private val aData = io.in.map(in => ShiftRegister(pack(in.bits), rankLevels, adv))
  private val aRank = (0 until lanes).map(k => if (k == 0) 0.U else sums(k - 1))
  private val aCount = sums.last

  private val full  = cnt >= ppl.U
  private val anyIn = valids.reduce(_ || _)
  private val flush = io.done && cnt =/= 0.U && !full && !anyIn && !anys.reduce(_ || _) && !bAny
  q.io.enq.valid     := full || flush
  q.io.enq.bits.line := line
  q.io.enq.bits.data := VecInit.tabulate(ppl)(k => Mux(k.U < cnt, slots(k), 0.U)).asUInt
  io.out <> q.io.deq
  private val leave = q.io.enq.fire
  private val leaveFull = full && q.io.enq.ready // a full line leaves (step 2's pairs may land)

  // Where step 2's pairs go: behind what stays once a leaving line is gone; they land when
  // all `lanes` would fit below `cap` there.
  private val base = Mux(leaveFull, cnt - ppl.U, Mux(leave, 0.U, cnt))
  private val bTake = Mux(leaveFull, cnt <= (cap - 1 - lanes + ppl).U, cnt <= (cap - 1 - lanes).U)
  private val bMoves = bAny && bTake
  adv := !aAny || !bAny || bTake

  for (in <- io.in) in.ready := adv
  when(adv && aAny) {
    bAny := true.B
    bCount := aCount
    for (j <- 0 until lanes) { // the j-th valid pair is lane k's with rank j
      val sel = (j until lanes).map(k => aValid(k) && aRank(k) === j.U)
      bHas(j) := sel.reduce(_ || _)
      bData(j) := Mux1H(sel, aData.drop(j))
    }
  }.elsewhen(bMoves) { bAny := false.B }

  for (s <- 0 until cap) {
    // Slot s takes step 2's pair s - base when there is one; else, as a full line leaves, the
    // slot a line above moves down.
    val from = (0 until lanes).filter(j => s - j >= 0)
    val hit = VecInit(from.map(j => base === (s - j).U && bHas(j))).asUInt
    val moved = if (s + ppl < cap) slots(s + ppl) else slots(s)
    slots(s) := Mux(bMoves && hit.orR, Mux1H(hit, from.map(bData(_))), Mux(leaveFull, moved, slots(s)))
  }
  cnt := base + Mux(bMoves, bCount, 0.U)
  when(leave) { line := line + 1.U; emitted := emitted + Mux(full, ppl.U, cnt) }
  when(io.start) { line := 0.U; emitted := 0.U; cnt := 0.U; bAny := false.B }

  io.emitted := emitted
  io.idle    := cnt === 0.U && !anys.reduce(_ || _) && !bAny && !q.io.deq.valid
}
