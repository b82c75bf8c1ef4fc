package collide.afu

import chisel3._
import chisel3.util._
import collide.world.WorldPair

/** World mode: packs the broad phase's candidate pairs, one a cycle from each of its `lanes`,
  * into pair lines for the dispatcher, exactly as the host lays out a pair list (u16 i, u16 j;
  * pair k of line l is candidate 16 l + k; the lanes' pairs of one cycle in lane order). A
  * lane's pair is taken when its slot is in the line: the rest wait a cycle, for the next
  * line (up to 16 lanes every waiting pair fits the next one; with 32, lanes past the next
  * line's room wait again, the lower lanes first). A line leaves when full, or
  * part-full once `done` says no candidate will follow. `emitted` counts the candidates in lines handed out; the dispatcher takes it
  * as the run's pair count, so a line's pairs are min(16, emitted - its first), which is the
  * line's own count (a part-full line is the last). Unused slots are zero. Up to `queue` lines
  * wait for the dispatcher (2 by default): a deeper queue lets the lanes run on while a burst of
  * contacts holds the SCPUs' results at the collector (docs/afu.md, "Starting ahead").
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

  private val slots   = Reg(Vec(ppl, UInt(32.W)))
  private val cnt     = RegInit(0.U(log2Ceil(ppl + 1).W))
  private val line    = RegInit(0.U(p.pairLineBits.W))
  private val emitted = RegInit(0.U((p.layout.pairIndexBits + 1).W))
  private val q = Module(new Queue(new PairLine(p.pairLineBits), queue) {
    override def desiredName = "WorldLineQueue" + (if (queue != 2) s"_d$queue" else "") + p.name
  })

  private val full = cnt === ppl.U
  private val anyIn = io.in.map(_.valid).reduce(_ || _)
  q.io.enq.valid     := full || (io.done && cnt =/= 0.U && !anyIn)
  q.io.enq.bits.line := line
  q.io.enq.bits.data := VecInit.tabulate(ppl)(k => Mux(k.U < cnt, slots(k), 0.U)).asUInt
  io.out <> q.io.deq

  // A full line must leave before the next pair lands; the leaving line frees slot 0. A lane's
  // pair lands after the held ones and the lower lanes' valid ones, if that slot exists.
  private val open = !full || q.io.enq.ready
  private val base = Mux(q.io.enq.fire, 0.U, cnt)
  private val room = ppl.U - base
  private val before = io.in.indices.map(k => PopCount(io.in.take(k).map(_.valid)))
  for ((in, k) <- io.in.zipWithIndex) {
    in.ready := open && before(k) < room
    when(in.fire) { slots(VecIndex(base + before(k))) := Cat(in.bits.j.pad(16), in.bits.i.pad(16)) }
  }
  private val taken = PopCount(io.in.map(_.fire))
  when(q.io.enq.fire) {
    line := line + 1.U; emitted := emitted + cnt
    cnt := taken
  }.elsewhen(taken =/= 0.U) { cnt := cnt + taken }
  when(io.start) { line := 0.U; emitted := 0.U; cnt := 0.U }

  io.emitted := emitted
  io.idle    := cnt === 0.U && !q.io.deq.valid

  private object VecIndex { def apply(i: UInt): UInt = i(log2Ceil(ppl) - 1, 0) }
}
