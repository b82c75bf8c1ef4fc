package collide.formal

import chisel3._
import chisel3.util._
import collide.afu._

/** PairDispatcher in an environment that offers pair lines (any line numbers below the run's
  * pair count, held until taken, the watched pair's line once), sphere data (zero: it plays
  * no part here), a `go` that stays up once up, and SCPU and group consumers that are ready
  * or not at will. It follows one watched pair index (a free input held from reset, so any
  * index) from its line into a group.
  *
  * Proven: the watched pair is dispatched (lies in a group that goes out) at most as often as
  * its line came in, and, whenever the block says idle, exactly as often; every group has
  * 1..lanes pairs; and the block's own assertion (no SCPU input queue overflow: its credits
  * are right). SeededBug: the wrapper misses the groups whose first pair is odd (a dropped
  * valid), so the idle check fails.
  */
class PairDispatcherFormal(p: PucParams, check: Check = Check.Prove) extends Module {
  private val n = p.scpus
  private val ppl = p.layout.pairsPerLine
  private val pw = p.layout.pairIndexBits
  val io = IO(new Bundle {
    val go          = Input(Bool())
    val numPairs    = Input(UInt(pw.W))
    val numSpheres  = Input(UInt(17.W))
    val pairs       = Flipped(Decoupled(new PairLine(p.pairLineBits)))
    val rdata       = Input(Vec(n, Vec(2, new Sphere(p.linkWidth))))
    val scpuReady   = Input(Vec(n, Bool()))
    val groupsReady = Input(Bool())
    val watch       = Input(UInt(pw.W))
  })
  val dut = Module(new PairDispatcher(p))
  dut.io.go := io.go
  dut.io.numPairs := io.numPairs
  dut.io.numSpheres := io.numSpheres
  dut.io.pairs <> io.pairs
  dut.io.rdata := io.rdata
  dut.io.world := false.B
  for (s <- 0 until n) dut.io.scpu(s).ready := io.scpuReady(s)
  dut.io.groups.ready := io.groupsReady

  // ---- the environment
  FormalEnv.producerHolds(io.pairs)
  // The pairs' sphere indices and the spheres read play no part in the counts: zero, for the solver.
  assume(io.pairs.bits.data === 0.U && io.rdata.asUInt === 0.U, "data zero")
  // go (the table is loaded) stays up once up, as the PUC latches it.
  when(RegNext(io.go, false.B)) { assume(io.go, "go stays up") }
  FormalEnv.stable(io.numPairs); FormalEnv.stable(io.numSpheres); FormalEnv.stable(io.watch)
  private val lineFirst = (io.pairs.bits.line << log2Ceil(ppl)).asUInt.pad(pw + 1)
  when(io.pairs.valid) { assume(lineFirst < io.numPairs, "a pair line lies below the run's pair count") }
  assume(io.watch < io.numPairs, "the watched pair is one of the run's")
  private val watchLine = io.watch >> log2Ceil(ppl)
  private val offersWatch = io.pairs.valid && io.pairs.bits.line === watchLine
  private val watchTaken = RegInit(false.B)
  when(io.pairs.fire && io.pairs.bits.line === watchLine) { watchTaken := true.B }
  assume(!(offersWatch && watchTaken), "the watched pair's line is offered once")

  // ---- the watched pair, followed from its line into a group. (One symbolic pair index rather
  // than sums over all pairs: a SAT solver proves a fact about one item quickly, an equality of
  // two long sums slowly, and the watched index is any index.)
  private val acceptedW = FormalEnv.counter((io.pairs.fire && io.pairs.bits.line === watchLine).asUInt, 2)
  private val g = dut.io.groups.bits
  private val inGroup = io.watch >= g.first && io.watch < g.first +& g.cnt
  /** A group the checker sees go (SeededBug: a group whose first pair has bit 1 set is missed, a dropped valid). */
  private val groupSeen = if (check == Check.SeededBug) dut.io.groups.fire && !g.first(1) else dut.io.groups.fire
  private val dispatchedW = FormalEnv.counter((groupSeen && inGroup).asUInt, 2)
  assert(dispatchedW <= acceptedW, "the watched pair is dispatched at most as often as it came in")
  when(dut.io.idle) { assert(dispatchedW === acceptedW, "idle: the watched pair, if it came in, was dispatched") }
  private val drained = dut.io.idle && !RegNext(dut.io.ren.asUInt.orR, false.B) && !dut.io.scpu.map(_.valid).reduce(_ || _)
  when(dut.io.groups.valid) {
    assert(dut.io.groups.bits.cnt =/= 0.U && dut.io.groups.bits.cnt <= p.lanes.U, "a group has 1..lanes pairs")
  }

  FormalEnv.finish(check, acceptedW === 1.U && dispatchedW === 1.U && drained,
    "the watched pair in and dispatched, everything drained")
}
