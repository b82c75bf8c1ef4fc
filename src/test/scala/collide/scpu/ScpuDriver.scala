package collide.scpu

import scala.util.Random
import chisel3._
import chisel3.util._
import chiseltest._
import collide.scpu.model._

/** One Scpu's ports with the payloads flattened (ScpuIn.asUInt, ScpuOut.asUInt), so a test
  * pokes one value and peeks one value per cycle instead of twenty: with Verilator the
  * per-call cost of chiseltest dominates the simulation.
  */
class ScpuPort(val cfg: ScpuConfig) extends Bundle {
  val in  = Flipped(Decoupled(UInt(ScpuPort.inWidth(cfg).W)))
  val out = Decoupled(UInt(ScpuPort.outWidth(cfg).W))
}

object ScpuPort {
  def inWidth(c: ScpuConfig): Int  = 8 * c.linkWidth + c.tagBits
  def outWidth(c: ScpuConfig): Int = 1 + 2 + 9 * c.linkWidth + 1 + collide.fp.FpFlags.width + c.tagBits

  /** ScpuIn.asUInt: the first field (x1) in the most significant bits, tag in the least. */
  def pack(c: ScpuConfig, p: ScpuPair, tag: BigInt): BigInt =
    (p.fields :+ tag).zip(Seq.fill(8)(c.linkWidth) :+ c.tagBits).foldLeft(BigInt(0)) { case (acc, (v, w)) => (acc << w) | v }

  /** ScpuOut from its asUInt. */
  def unpack(c: ScpuConfig, bits: BigInt): ScpuResult = {
    var b = bits
    def take(w: Int): BigInt = { val v = b & ((BigInt(1) << w) - 1); b >>= w; v }
    val tag = take(c.tagBits); val flags = take(collide.fp.FpFlags.width).toInt; val nonFinite = take(1) == 1
    val Seq(w, d, depth, nz, ny, nx, pz, py, px) = Seq.fill(9)(take(c.linkWidth))
    val kind = take(2).toInt; val hit = take(1) == 1
    ScpuResult(hit, kind, px, py, pz, nx, ny, nz, depth, nonFinite, flags, tag, d, w)
  }
}

/** Several independent Scpus in one module, so one Verilator build serves every preset
  * (building is what costs: a minute each; simulating 20,000 pairs takes seconds).
  */
class ScpuBank(val cfgs: Seq[ScpuConfig]) extends Module {
  val io = IO(MixedVec(cfgs.map(c => new ScpuPort(c))))
  val latencies: Seq[Int] = cfgs.zipWithIndex.map { case (c, i) =>
    val s = Module(new Scpu(c))
    s.io.in.valid := io(i).in.valid
    s.io.in.bits  := io(i).in.bits.asTypeOf(s.io.in.bits)
    io(i).in.ready := s.io.in.ready
    io(i).out.valid := s.io.out.valid
    io(i).out.bits  := s.io.out.bits.asUInt
    s.io.out.ready := io(i).out.ready
    s.latency
  }
  // Named by its configurations; a long list by a hash of it (Verilator's top-module lookup
  // failed on a 180-character name).
  override def desiredName = {
    val ids = cfgs.map(_.id).mkString("_")
    "ScpuBank_" + (if (ids.length <= 100) ids else f"${cfgs.size}_${ids.hashCode & 0xffffffffL}%08x")
  }
}

/** Streams pairs through one Scpu over its valid/ready handshake and checks every result
  * against `expected`: input valid drops at random (bubbles), out.ready drops at random
  * (stalls). While out.valid is high the output is checked every cycle, stalled or not, so a
  * stall that fails to hold the result is caught. With no stalls and no bubbles it also
  * checks that every result appears exactly `latency` cycles after its pair was accepted.
  * `extra` checks each result once more (e.g. against an independent oracle).
  * Call cycle() once per clock, before stepping.
  */
final class ScpuLane(port: ScpuPort, latency: Int, pairs: IndexedSeq[ScpuPair], expected: IndexedSeq[ScpuResult],
                     rng: Random, stallPercent: Int, bubblePercent: Int, labels: IndexedSeq[String] = IndexedSeq.empty,
                     extra: (Int, ScpuResult) => Unit = (_, _) => ()) {
  require(pairs.length == expected.length)
  private val n = pairs.length
  private val cfg = port.cfg
  private val tagMod = BigInt(1) << math.min(cfg.tagBits, 30)
  private var sent = 0
  private var lastPoked = -1
  private val acceptedAt = new Array[Int](n)
  var recv = 0
  var cycles = 0
  def done: Boolean = recv >= n

  def cycle(): Unit = {
    if (done) { port.in.valid.poke(false.B); port.out.ready.poke(true.B); return }
    val v = sent < n && rng.nextInt(100) >= bubblePercent
    port.in.valid.poke(v.B)
    if (v && lastPoked != sent) {
      port.in.bits.poke(ScpuPort.pack(cfg, pairs(sent), BigInt(sent) % tagMod).U)
      lastPoked = sent
    }
    val ready = rng.nextInt(100) >= stallPercent
    port.out.ready.poke(ready.B)
    if (port.out.valid.peekBoolean()) {
      assert(recv < n, s"${cfg.name} cycle $cycles: a result beyond the $n pairs sent")
      val got = ScpuPort.unpack(cfg, port.out.bits.peekInt())
      val want = expected(recv).copy(tag = BigInt(recv) % tagMod)
      assert(got == want,
        s"${cfg.name} pair $recv${labels.lift(recv).map(" (" + _ + ")").getOrElse("")} cycle $cycles:\n  in   ${pairs(recv)}\n  got  ${got.show}\n  want ${want.show}")
      if (stallPercent == 0 && bubblePercent == 0)
        assert(cycles - acceptedAt(recv) == latency, s"${cfg.name} pair $recv: result after ${cycles - acceptedAt(recv)} cycles, latency is $latency")
      if (ready) { extra(recv, got); recv += 1 }
    }
    val inReady = port.in.ready.peekBoolean()
    if (v && inReady) { acceptedAt(sent) = cycles; sent += 1 }
    cycles += 1
  }
}

object ScpuDriver {
  /** Runs lanes in lockstep until all are done; returns the cycles taken. */
  def run(clock: Clock, lanes: Seq[ScpuLane], limit: Int): Int = {
    var cycles = 0
    while (!lanes.forall(_.done)) {
      lanes.foreach(_.cycle())
      clock.step()
      cycles += 1
      assert(cycles < limit, s"no progress after $cycles cycles (${lanes.map(l => l.recv).mkString(",")} results)")
    }
    cycles
  }
}
