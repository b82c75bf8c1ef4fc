package collide.world

import chisel3._
import chisel3.util._

/** A range of the sorted table (or of sphere indices) to stream, and what travels with it.
  * With `groups` sorted tables (a sort split by index, BroadPhaseParams.sortGroups), a range
  * is one run in each, streamed in group order: a bucket's entries in index order. */
class StreamRange[T <: Data](tagType: T, countW: Int, groups: Int = 1) extends Bundle {
  val begin = Vec(groups, UInt(countW.W))
  val end = Vec(groups, UInt(countW.W))
  /** Positions are sphere indices (the large pass, the scatter): no entry read; group 0 only. */
  val direct = Bool()
  val tag = tagType.cloneType
}

object StreamRange {
  /** Bits of a group number. */
  def groupW(groups: Int): Int = math.max(1, log2Ceil(groups))
}

class StreamItem[T <: Data](tagType: T, itemW: Int, countW: Int, cellBits: Int, qWidth: Int, groups: Int = 1) extends Bundle {
  val group = UInt(StreamRange.groupW(groups).W) // which sorted table (0 with one group, and when direct)
  val pos = UInt(countW.W)  // position in the sorted table (direct: the index)
  val item = UInt(itemW.W)  // the sphere index
  val mark = Bool()         // the entry's mark bit (false when direct)
  val rec = new KeyRecord(cellBits, qWidth)
  val tag = tagType.cloneType
}

/** A position in flight between KeyStream's two reads. */
class StreamStage[T <: Data](tagType: T, countW: Int, groups: Int) extends Bundle {
  val group = UInt(StreamRange.groupW(groups).W)
  val pos = UInt(countW.W)
  val direct = Bool()
  val tag = tagType.cloneType
}

/** A position past its entry read, waiting for its key record. */
class StreamKeyStage[T <: Data](tagType: T, itemW: Int, countW: Int, groups: Int) extends Bundle {
  val group = UInt(StreamRange.groupW(groups).W)
  val pos = UInt(countW.W)
  val tag = tagType.cloneType
  val item = UInt(itemW.W)
  val mark = Bool()
}

/** Streams ranges of the broad phase's sorted table: for each position the entry (sphere
  * index and mark) from BucketSort, a cycle later, then that sphere's key record,
  * `keyLatency` cycles after its address (the broad phase recomputes it from the sphere
  * table), one position a cycle. Ranges follow each other without a gap (an empty range
  * costs its accepting cycle), and so do a range's runs in its groups' tables. The reads never
  * stall: a position is read only when the output queue has room for everything in flight,
  * so `out` may apply back-pressure.
  */
class KeyStream[T <: Data](tag: T, itemW: Int, countW: Int, cellBits: Int, qWidth: Int, keyLatency: Int = 1,
                           groups: Int = 1)
    extends Module {
  require(keyLatency >= 1, s"keyLatency must be >= 1, got $keyLatency")
  require(Seq(1, 2, 4, 8).contains(groups), s"groups must be 1, 2, 4 or 8, got $groups")
  private val gW = StreamRange.groupW(groups)
  private val depth = keyLatency + 3 // everything in flight, plus one: full rate when out is ready
  val io = IO(new Bundle {
    val req = Flipped(Decoupled(new StreamRange(tag, countW, groups)))
    val entryAddr = Output(UInt(itemW.W))
    val entryGroup = Output(UInt(gW.W)) // the table entryAddr is in
    val entryItem = Input(UInt(itemW.W)) // a cycle after entryAddr
    val entryMark = Input(Bool())
    val keyAddr = Output(UInt(itemW.W))
    val keyData = Input(new KeyRecord(cellBits, qWidth)) // keyLatency cycles after keyAddr
    val out = Decoupled(new StreamItem(tag, itemW, countW, cellBits, qWidth, groups))
    /** No range held, nothing in flight or queued. */
    val idle = Output(Bool())
  })

  private val cur = Reg(new StreamRange(tag, countW, groups))
  private val busy = RegInit(false.B)
  private val q = Module(new Queue(new StreamItem(tag, itemW, countW, cellBits, qWidth, groups), depth))

  private val s1v = RegInit(false.B); private val s1 = Reg(new StreamStage(tag, countW, groups))
  private val kv = Seq.fill(keyLatency)(RegInit(false.B))
  private val ks = Seq.fill(keyLatency)(Reg(new StreamKeyStage(tag, itemW, countW, groups)))

  // What is queued or in flight (the queue's count plus every stage's valid), kept as one
  // register: adding them up each cycle was a long path through `room` into req.ready.
  private val used = RegInit(0.U(log2Ceil(depth + 1).W))
  private val room = used < depth.U
  private val issue = busy && room
  used := used + issue.asUInt - q.io.deq.fire.asUInt
  // Per group, registered as cur changes (so req.ready does not wait on compares of cur):
  // positions left (cur.begin =/= cur.end), and exactly one left (cur.begin + 1 === cur.end).
  private val left = Reg(Vec(groups, Bool()))
  private val single = Reg(Vec(groups, Bool()))
  // The group read from: the first with positions left (group 1 once group 0's run is done).
  private val g = if (groups == 1) 0.U(1.W) else PriorityEncoder(left.asUInt)
  private val at = if (groups == 1) cur.begin(0) else cur.begin(g)
  private val moreAfter =
    if (groups == 1) !single(0)
    else !single(g) || (0 until groups).map(h => left(h) && h.U > g).reduce(_ || _)
  private val last = issue && !moreAfter
  io.req.ready := !busy || last
  when(issue) { if (groups == 1) cur.begin(0) := at + 1.U else cur.begin(g) := at + 1.U }
  for (h <- 0 until groups) when(issue && g === h.U) {
    left(h) := !single(h); single(h) := cur.begin(h) + 2.U === cur.end(h)
  }
  when(last) { busy := false.B }
  when(io.req.fire) {
    cur := io.req.bits
    busy := (0 until groups).map(q => io.req.bits.begin(q) =/= io.req.bits.end(q)).reduce(_ || _)
    for (h <- 0 until groups) {
      left(h) := io.req.bits.begin(h) =/= io.req.bits.end(h)
      single(h) := io.req.bits.begin(h) + 1.U === io.req.bits.end(h)
    }
  }

  io.entryAddr := at(itemW - 1, 0)
  io.entryGroup := g
  s1v := issue
  when(issue) { s1.group := g; s1.pos := at; s1.direct := cur.direct; s1.tag := cur.tag }

  private val item = Mux(s1.direct, s1.pos(itemW - 1, 0), io.entryItem)
  io.keyAddr := item
  kv.head := s1v
  when(s1v) {
    ks.head.group := s1.group; ks.head.pos := s1.pos; ks.head.tag := s1.tag; ks.head.item := item; ks.head.mark := !s1.direct && io.entryMark
  }
  for (i <- 1 until keyLatency) { kv(i) := kv(i - 1); ks(i) := ks(i - 1) }

  q.io.enq.valid := kv.last
  q.io.enq.bits.group := ks.last.group
  q.io.enq.bits.pos := ks.last.pos
  q.io.enq.bits.item := ks.last.item
  q.io.enq.bits.mark := ks.last.mark
  q.io.enq.bits.rec := io.keyData
  q.io.enq.bits.tag := ks.last.tag
  assert(!kv.last || q.io.enq.ready, "KeyStream: a read came back with no room (credit accounting)")
  io.out <> q.io.deq
  io.idle := !busy && !s1v && !kv.reduce(_ || _) && !q.io.deq.valid
}
