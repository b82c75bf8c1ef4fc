package collide.formal

import chisel3._
import chisel3.util._
import collide.world.BucketSort

/** BucketSort through one whole world: clear, count every item, prefix, scatter every item
  * again, then one lookup and one entry read. The world (up to `items` items, each bucket any
  * value) and a watched item and bucket are free but stable; each port offers its items when
  * it likes, port p the p-th part of them as the broad phase splits the table (the first
  * floor(n / 2) items to port 0). Uninitialised counter and entry memories hold anything, so
  * the clear pass is checked too. The prefix sum's pipeline registers have no reset: they
  * flush in its depth of idle cycles, and until then they may write the counters and end a
  * pass early (as the first check found). So the wrapper starts its clear once they have
  * flushed, as a caller does that starts a world well after reset (the broad phase waits
  * for the host's start), or as a reset held that long would.
  *
  * Proven, once the world is sorted: the watched bucket's begin and end are the number of
  * items below it and at or below it; the watched item sits at its place in the stable sort
  * (the items below its bucket, then those of its bucket before it); counted and scattered are
  * the world's size; no bucket was refused. The watched item and bucket are arbitrary, so this
  * holds for every one of them.
  *
  * SeededBug: the wrapper drops item 0's valid in the scatter pass (it moves on as if it had
  * been taken), so one item fewer is scattered and the places after it are off. */
class BucketSortFormal(items: Int, bucketsLog2: Int, wordLog2: Int, ports: Int, check: Check = Check.Prove) extends Module {
  private val nW = log2Ceil(items + 1)
  private val iW = log2Ceil(items)
  val io = IO(new Bundle {
    val buckets = Input(Vec(items, UInt(bucketsLog2.W)))
    val n = Input(UInt(nW.W))
    val go = Input(Vec(ports, Bool()))
    val watchItem = Input(UInt(iW.W))
    val watchBucket = Input(UInt(bucketsLog2.W))
  })
  Seq(io.buckets, io.n, io.watchItem, io.watchBucket).foreach(FormalEnv.stable)
  assume(io.n <= items.U, "at most items items")

  val dut = Module(new BucketSort(items, bucketsLog2, wordLog2, copies = 1, ports = ports))
  dut.io.usedLog2 := bucketsLog2.U
  dut.io.walkBuckets := (1 << bucketsLog2).U
  dut.io.clear := false.B
  dut.io.prefix := false.B
  dut.io.mark(0).valid := false.B
  dut.io.mark(0).bits := DontCare
  dut.io.lookup(0).bucket := io.watchBucket
  dut.io.entry(0).addr := 0.U

  // The golden sort, combinational over the stable world.
  private def present(j: Int): Bool = j.U < io.n
  private def countWhere(f: Int => Bool): UInt = PopCount((0 until items).map(j => present(j) && f(j)))
  private val wantBegin = countWhere(j => io.buckets(j) < io.watchBucket)
  private val wantEnd = countWhere(j => io.buckets(j) <= io.watchBucket)
  private val wb = io.buckets(io.watchItem)
  private val wantPlace = countWhere(j => io.buckets(j) < wb) +& countWhere(j => j.U < io.watchItem && io.buckets(j) === wb)

  // Port p streams items [from(p), to(p)).
  private val half = io.n >> 1
  private def from(p: Int): UInt = if (ports == 1 || p == 0) 0.U else half
  private def to(p: Int): UInt = if (ports == 1 || p == 1) io.n else half

  private object S extends ChiselEnum { val warm, clear, clearing, count, prefix, summing, scatter, settle, read, verify, done = Value }
  private val state = RegInit(S.warm)
  private val warmCycles = BucketSort.prefixStages(1 << math.min(wordLog2, bucketsLog2)) + 1
  private val sinceReset = FormalEnv.cycles(log2Ceil(warmCycles + 1))
  private val next = Reg(Vec(ports, UInt(nW.W)))
  private val settle = RegInit(0.U(2.W))
  private def streaming = state === S.count || state === S.scatter
  private def allSent = (0 until ports).map(p => next(p) === to(p)).reduce(_ && _)
  private def restart(): Unit = for (p <- 0 until ports) next(p) := from(p)

  for ((in, p) <- dut.io.in.zipWithIndex) {
    val k = next(p)
    val skip = if (check == Check.SeededBug) state === S.scatter && k === 0.U && k =/= to(p) else false.B
    in.valid := streaming && io.go(p) && k =/= to(p) && !skip
    in.bits.scatter := state === S.scatter
    in.bits.bucket := io.buckets(k(iW - 1, 0))
    in.bits.item := k(iW - 1, 0)
    when(in.fire || skip) { k := k + 1.U }
  }

  switch(state) {
    is(S.warm) { when(sinceReset === (warmCycles - 1).U) { state := S.clear } }
    is(S.clear) { dut.io.clear := true.B; state := S.clearing }
    is(S.clearing) { when(!dut.io.busy) { state := S.count; restart() } }
    is(S.count) { when(allSent) { state := S.prefix } }
    is(S.prefix) { dut.io.prefix := true.B; state := S.summing }
    is(S.summing) { when(!dut.io.busy) { state := S.scatter; restart() } }
    // The last placement is written the cycle after its fire.
    is(S.scatter) { when(allSent) { state := S.settle; settle := 0.U } }
    is(S.settle) { settle := settle + 1.U; when(settle === 1.U) { state := S.read } }
    is(S.read) { state := S.verify }
    is(S.verify) { state := S.done }
  }
  when(state === S.read || state === S.verify) { dut.io.entry(0).addr := wantPlace(iW - 1, 0) }

  when(state === S.verify) {
    assert(dut.io.lookup(0).begin === wantBegin, "the watched bucket begins after the items below it")
    assert(dut.io.lookup(0).end === wantEnd, "the watched bucket ends after its own items")
    when(io.watchItem < io.n) { assert(dut.io.entry(0).item === io.watchItem, "the watched item is at its stable place") }
    assert(dut.io.counted === io.n && dut.io.scattered === io.n, "every item counted and scattered once")
    assert(!dut.io.badBucket, "no bucket refused")
  }
  // Finish: a full world sorted, every item in the watched bucket (two items or more).
  FormalEnv.finish(check, state === S.done && io.n === items.U && wantEnd - wantBegin >= 2.U,
    "a full world sorted, with a shared bucket watched")
}
