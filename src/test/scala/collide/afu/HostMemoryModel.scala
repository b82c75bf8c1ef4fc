package collide.afu

import chisel3._
import chiseltest._
import scala.collection.mutable

/** How the modelled link behaves. Latencies are in cycles, drawn uniformly from [min, max];
  * `reorder`: a response is picked at random among those due (else oldest first);
  * `*Ready`: probability that rdReq/wrReq is ready in a cycle (back-pressure). */
final case class LinkBehaviour(
    rdLatency: (Int, Int) = (1, 1),
    wrLatency: (Int, Int) = (1, 1),
    reorder: Boolean = false,
    rdReady: Double = 1.0,
    wrReady: Double = 1.0) {
  def name: String = s"rd${rdLatency._1}-${rdLatency._2}_wr${wrLatency._1}-${wrLatency._2}" +
    (if (reorder) "_reorder" else "") + f"_bp$rdReady%.2f/$wrReady%.2f"
}
object LinkBehaviour {
  /** 1-cycle latency, no back-pressure, in order: the cycle report's memory. */
  val ideal = LinkBehaviour()
  /** A hostile link: long, random, reordered latencies and frequent back-pressure. */
  val hostile = LinkBehaviour((1, 60), (1, 40), reorder = true, rdReady = 0.6, wrReady = 0.5)
  /** About HARP v1 at 200 MHz: a read round trip of 200-290 ns is 40-58 cycles (docs/host.md, link presets). */
  val harp = LinkBehaviour((40, 58), (30, 50), reorder = true, rdReady = 0.9, wrReady = 0.9)
}

/** One write the AFU made: the cycle of its request, the line and the data. */
final case class WriteEvent(cycle: Long, addr: BigInt, data: BigInt, respondedBefore: Int)

/** TEST ONLY: host shared memory plus the CCI link, driven cycle by cycle through chiseltest.
  * Seeded: the same seed gives the same latencies, order and back-pressure. It checks the
  * link rules as it goes: no more requests in flight than the AFU's limits, no response
  * tag reused while in flight.
  * `skipIdle`: while the AFU reports idle and no response is due, one clock edge with
  * `skipCycles = n` stands for the n cycles up to the next response (the AFU's io.idle
  * contract, docs/afu-interface.md); the random stream is drawn as if stepped, so a run
  * with skipping must equal the same run stepped cycle by cycle. */
class HostMemoryModel(link: LinkIO, clock: Clock, beh: LinkBehaviour, seed: Long,
                      maxReads: Int, maxWrites: Int, skipIdle: Boolean = false) {
  private val rnd = new scala.util.Random(seed)
  val mem = mutable.Map[BigInt, BigInt]().withDefaultValue(BigInt(0))
  val writes = mutable.ArrayBuffer[WriteEvent]()
  private val pendingRd = mutable.ArrayBuffer[(Long, BigInt, BigInt)]() // due, tag, data
  private val pendingWr = mutable.ArrayBuffer[(Long, BigInt, BigInt)]() // due, tag, line
  /** Lines whose write has been acknowledged: what a host polling its memory can see (a run
    * queue's host starts the next run once a status line is here). */
  val committed = mutable.Set[BigInt]()
  private val rdTags = mutable.Set[BigInt](); private val wrTags = mutable.Set[BigInt]()
  var cycle = 0L
  var trace: Option[() => String] = None
  var writesResponded = 0
  var maxRdInFlight = 0; var maxWrInFlight = 0
  var cyclesSkipped = 0L
  private val skipPorts = link match { case a: AfuIO => Some(a); case _ => None }
  require(!skipIdle || skipPorts.isDefined, "HostMemoryModel: skipIdle needs the AFU's idle/skipCycles ports")
  skipPorts.foreach(_.skipCycles.poke(0.U))
  private var csrPresented = false

  private def draw(r: (Int, Int)) = r._1 + rnd.nextInt(r._2 - r._1 + 1)
  private def pick[T](due: Seq[T]): T = if (beh.reorder) due(rnd.nextInt(due.size)) else due.head

  def writeCsr(index: Int, value: BigInt): Unit = {
    link.csr.valid.poke(true.B); link.csr.bits.index.poke(index.U); link.csr.bits.data.poke(value.U(64.W))
    csrPresented = true
    step(); link.csr.valid.poke(false.B)
    csrPresented = false
  }

  /** Jumps to the next response when the AFU idles until then; true if it did. */
  private def trySkip(): Boolean = {
    val next = (pendingRd.map(_._1) ++ pendingWr.map(_._1)).minOption
    val n = next.map(_ - cycle).getOrElse(0L)
    if (!skipIdle || csrPresented || n < 2 || !skipPorts.get.idle.peek().litToBoolean) return false
    link.rdResp.valid.poke(false.B); link.wrResp.valid.poke(false.B)
    for (_ <- 0L until n) { rnd.nextDouble(); rnd.nextDouble() } // the ready draws of n stepped cycles
    skipPorts.get.skipCycles.poke(n.U)
    clock.step()
    skipPorts.get.skipCycles.poke(0.U)
    cycle += n; cyclesSkipped += n
    true
  }

  /** One clock cycle of the link. */
  def step(): Unit = {
    if (trySkip()) return
    // responses due this cycle (one read, one write response a cycle)
    val rdDue = pendingRd.filter(_._1 <= cycle).toSeq
    if (rdDue.nonEmpty) {
      val r = pick(rdDue); pendingRd -= r; rdTags -= r._2
      link.rdResp.valid.poke(true.B); link.rdResp.bits.tag.poke(r._2.U); link.rdResp.bits.data.poke(r._3.U(512.W))
      trace.foreach(t => println(s"$cycle rdResp tag ${r._2} ${t()}"))
    } else link.rdResp.valid.poke(false.B)
    val wrDue = pendingWr.filter(_._1 <= cycle).toSeq
    if (wrDue.nonEmpty) {
      val w = pick(wrDue); pendingWr -= w; wrTags -= w._2; writesResponded += 1; committed += w._3
      link.wrResp.valid.poke(true.B); link.wrResp.bits.tag.poke(w._2.U)
    } else link.wrResp.valid.poke(false.B)
    // requests
    val rdReady = rnd.nextDouble() < beh.rdReady
    val wrReady = rnd.nextDouble() < beh.wrReady
    link.rdReq.ready.poke(rdReady.B); link.wrReq.ready.poke(wrReady.B)
    if (rdReady && link.rdReq.valid.peek().litToBoolean) {
      val tag = link.rdReq.bits.tag.peek().litValue; val addr = link.rdReq.bits.addr.peek().litValue
      assert(!rdTags.contains(tag), s"cycle $cycle: read tag $tag reused while in flight")
      rdTags += tag
      trace.foreach(t => println(s"$cycle rdReq tag $tag addr 0x${addr.toString(16)} ${t()}"))
      pendingRd += ((cycle + draw(beh.rdLatency), tag, mem(addr)))
      maxRdInFlight = maxRdInFlight.max(rdTags.size)
      assert(rdTags.size <= maxReads, s"cycle $cycle: ${rdTags.size} reads in flight, limit $maxReads")
    }
    if (wrReady && link.wrReq.valid.peek().litToBoolean) {
      val tag = link.wrReq.bits.tag.peek().litValue; val addr = link.wrReq.bits.addr.peek().litValue
      val data = link.wrReq.bits.data.peek().litValue
      assert(!wrTags.contains(tag), s"cycle $cycle: write tag $tag reused while in flight")
      wrTags += tag
      writes += WriteEvent(cycle, addr, data, writesResponded)
      mem(addr) = data
      pendingWr += ((cycle + draw(beh.wrLatency), tag, addr))
      maxWrInFlight = maxWrInFlight.max(wrTags.size)
      assert(wrTags.size <= maxWrites, s"cycle $cycle: ${wrTags.size} writes in flight, limit $maxWrites")
    }
    clock.step(); cycle += 1
  }

  def idleLink(): Boolean = pendingRd.isEmpty && pendingWr.isEmpty
}
