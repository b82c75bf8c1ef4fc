package collide.formal

import chisel3._
import chisel3.util._
import collide.afu._

/** ReadEngine (with its TagPool) in a run: `start` in the first cycle after reset, the run on
  * (`active`) from the next; the line counts and bases hold from reset; the read channel
  * takes requests when it likes; responses come back in any order, one a cycle, each for a
  * tag in flight (the wrapper's own record of requests and responses) and at least a cycle
  * after its request; the dispatcher takes pair lines when it likes. The wrapper keeps what
  * each tag asked for (a sphere or a pair line, which line) and the data of one watched pair
  * line's response.
  *
  * Proven: no request reuses a tag in flight, tags are below maxReads, the engine's count of
  * reads in flight is the wrapper's and never above maxReads; the k-th sphere request reads
  * sphereBase + k and the k-th pair request pairBase + k (the split adder of lineAddr), never
  * more than the run's lines, no pair before every sphere line is asked for; every response
  * is routed by its own tag: a sphere line is written to the table as the line it asked for,
  * with the response's data; the pair lines reach the dispatcher at most as often as their
  * responses came, and the watched pair line leaves once, with its line number and data;
  * `loaded` only once every sphere line is in; and the engine's own assertions (no pair line
  * without room, no response for a tag not in flight). SeededBug: the wrapper misses the
  * request of tag 1 (a dropped valid), so the engine's count of reads in flight is off. */
class ReadEngineFormal(p: PucParams, check: Check = Check.Prove) extends Module {
  private val nTags = p.maxReads
  private val tw = log2Ceil(nTags)
  private val cw = 8
  private val spLineBits = math.max(p.sphereLineBits, 1)
  val io = IO(new Bundle {
    val sphereBase  = Input(UInt(Link.addrBits.W))
    val sphereLines = Input(UInt((p.sphereLineBits + 1).W))
    val pairBase    = Input(UInt(Link.addrBits.W))
    val pairLines   = Input(UInt((p.pairLineBits + 1).W))
    val reqReady    = Input(Bool())
    val resp        = Flipped(Valid(new RdResp(p.tagBits)))
    val pairsReady  = Input(Bool())
    val watch       = Input(UInt(cw.W)) // a pair line number
  })
  val dut = Module(new ReadEngine(p))
  private val cyc = FormalEnv.cycles(4)
  dut.io.start := cyc === 0.U
  dut.io.active := cyc =/= 0.U
  dut.io.sphereBase := io.sphereBase
  dut.io.sphereLines := io.sphereLines
  dut.io.pairBase := io.pairBase
  dut.io.pairLines := io.pairLines
  dut.io.rdReq.ready := io.reqReady
  dut.io.rdResp := io.resp
  dut.io.pairs.ready := io.pairsReady

  // ---- the environment
  Seq(io.sphereBase, io.sphereLines, io.pairBase, io.pairLines, io.watch).foreach(FormalEnv.stable)
  assume(io.sphereLines <= (p.maxSpheres / p.layout.spheresPerLine).U, "at most the table's lines")
  assume(io.pairLines < (1 << cw).U, "the pair lines counted in the wrapper's width")
  // The wrapper's tags in flight, and what each asked for.
  val inFlight = RegInit(0.U(nTags.W))
  val askedPair = Reg(Vec(nTags, Bool()))
  val askedLine = Reg(Vec(nTags, UInt(cw.W)))
  private val req = dut.io.rdReq
  private val reqTag = req.bits.tag(tw - 1, 0)
  private val seen = if (check == Check.SeededBug) req.fire && reqTag =/= 1.U else req.fire
  private val rTag = io.resp.bits.tag(tw - 1, 0)
  when(io.resp.valid) { assume(io.resp.bits.tag < nTags.U && inFlight(rTag), "a response is for a tag in flight") }
  inFlight := (inFlight | Mux(seen, UIntToOH(reqTag, nTags), 0.U)) & ~Mux(io.resp.valid, UIntToOH(rTag, nTags), 0.U)

  // ---- requests
  val spheresAsked = RegInit(0.U(cw.W))
  val pairsAsked = RegInit(0.U(cw.W))
  private val isSphere = spheresAsked < io.sphereLines // what the k-th request must be
  when(req.valid) {
    assert(req.bits.tag < nTags.U, "a tag is below maxReads")
    assert(!inFlight(reqTag), "no request reuses a tag in flight")
    assert(spheresAsked < io.sphereLines || pairsAsked < io.pairLines, "no request past the run's lines")
    assert(req.bits.addr === Mux(isSphere, io.sphereBase + spheresAsked, io.pairBase + pairsAsked),
      "the k-th sphere (pair) request reads line k of the table (list)")
  }
  when(seen) {
    when(isSphere) { spheresAsked := spheresAsked + 1.U }.otherwise { pairsAsked := pairsAsked + 1.U }
    askedPair(reqTag) := !isSphere
    askedLine(reqTag) := Mux(isSphere, spheresAsked, pairsAsked)
  }
  assert(dut.io.outstanding === PopCount(inFlight), "the engine's reads in flight are the wrapper's")
  assert(PopCount(inFlight) <= nTags.U, "never more reads in flight than tags")

  // ---- responses
  val spheresGot = RegInit(0.U(cw.W))
  val pairsGot = RegInit(0.U(cw.W))
  private val wr = dut.io.sphereWrite
  when(io.resp.valid) {
    when(askedPair(rTag)) {
      pairsGot := pairsGot + 1.U
      assert(!wr.valid, "a pair line is not written to the sphere table")
    }.otherwise {
      spheresGot := spheresGot + 1.U
      assert(wr.valid && wr.bits.line === askedLine(rTag) && wr.bits.data === io.resp.bits.data,
        "a sphere line is written as the line its tag asked for, with its data")
    }
  }.otherwise { assert(!wr.valid, "no table write without a response") }
  when(dut.io.loaded) { assert(spheresGot === io.sphereLines, "loaded: every sphere line is in") }

  // ---- pair lines to the dispatcher; the watched one's data
  val pairsOut = RegInit(0.U(cw.W))
  private val out = dut.io.pairs
  when(out.fire) { pairsOut := pairsOut + 1.U }
  assert(pairsOut <= pairsGot, "no pair line leaves before its response came")
  private val watchData = Reg(UInt(Link.lineBits.W))
  private val watchGot = RegInit(false.B)
  when(io.resp.valid && askedPair(rTag) && askedLine(rTag) === io.watch) { watchData := io.resp.bits.data; watchGot := true.B }
  private val watchOut = RegInit(0.U(2.W))
  when(out.fire && out.bits.line === io.watch) {
    watchOut := watchOut + 1.U
    assert(watchGot && watchOut === 0.U && out.bits.data === watchData, "the watched pair line leaves once, with its data")
  }
  when(pairsOut === pairsGot && watchGot) { assert(watchOut === 1.U, "all out: the watched pair line left") }

  FormalEnv.finish(check, io.sphereLines =/= 0.U && io.pairLines =/= 0.U && dut.io.loaded && pairsOut === io.pairLines &&
    dut.io.outstanding === 0.U, "every sphere line in, every pair line out, nothing in flight")
}
