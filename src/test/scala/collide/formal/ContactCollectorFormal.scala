package collide.formal

import chisel3._
import chisel3.util._
import collide.afu._
import collide.scpu.ScpuOut

/** ContactCollector in dense mode (a record for every pair), fed groups (1..lanes pairs, any
  * base and first, held until taken) and SCPU results (any bits, held until taken) at will,
  * with a packer whose room is any number up to R a cycle.
  *
  * Proven: never more records a cycle than room; the records out and the pairs counted keep in
  * step (a group's pairs are counted once its last record has gone, so the records out lead
  * the pairs counted by at most one group: 0..lanes); the pairs counted never pass the pairs
  * of the groups taken. The results' values and the groups' first pair are zero: they play
  * no part in the counts. SeededBug: the wrapper counts a cycle's records twice when R go at once (a double count). */
class ContactCollectorFormal(p: PucParams, check: Check = Check.Prove) extends Module {
  private val n = p.scpus
  private val L = p.lanes
  private val R = p.layout.recordsPerLine
  private val cw = 8
  val io = IO(new Bundle {
    val groups = Flipped(Decoupled(new GroupInfo(p)))
    val scpu   = Vec(n, Flipped(Decoupled(new ScpuOut(p.linkWidth, p.scpuTagBits))))
    val room   = Input(UInt(log2Ceil(R + 1).W))
  })
  val dut = Module(new ContactCollector(p))
  dut.io.dense := true.B
  dut.io.keepFlagged := false.B
  dut.io.groups <> io.groups
  for (s <- 0 until n) dut.io.scpu(s) <> io.scpu(s)
  dut.io.room := io.room

  // ---- the environment
  FormalEnv.producerHolds(io.groups)
  for (s <- 0 until n) FormalEnv.producerHolds(io.scpu(s))
  when(io.groups.valid) { assume(io.groups.bits.cnt =/= 0.U && io.groups.bits.cnt <= L.U && io.groups.bits.base < n.U, "a group has 1..lanes pairs") }
  assume(io.room <= R.U, "the packer's room is at most a line")
  // The results' values play no part in the counts: zero, for the solver.
  for (s <- 0 until n) assume(io.scpu(s).bits.asUInt === 0.U, "results zero")
  assume(io.groups.bits.first === 0.U && io.groups.bits.invalid === 0.U, "group's first and invalid zero")

  // ---- the checks
  assert(dut.io.nRecs <= io.room, "never more records than room")
  private val counted = if (check == Check.SeededBug) Mux(dut.io.nRecs === R.U, (2 * R).U, dut.io.nRecs) else dut.io.nRecs
  val recsOut = FormalEnv.counter(counted, cw)
  val pairsCounted = FormalEnv.counter(dut.io.nPairs, cw)
  val pairsTaken = FormalEnv.counter(Mux(io.groups.fire, io.groups.bits.cnt, 0.U), cw)
  assert(recsOut >= pairsCounted && recsOut - pairsCounted <= L.U, "records out lead the pairs counted by at most a group")
  assert(pairsCounted <= pairsTaken, "no pair counted that was not taken")
  FormalEnv.finish(check, pairsCounted >= 2.U && pairsCounted === pairsTaken && recsOut === pairsCounted,
    "two groups' pairs counted, every record out")
}
