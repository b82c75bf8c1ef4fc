package collide.afu

import chisel3._
import chiseltest._

/** One contact record, decoded: the layout's value fields as link words (full: px, py, pz,
  * nx, ny, nz, depth; derived: d, w), the pair index and the record flags. */
final case class AfuRecord(fields: Seq[BigInt], pair: Int, flags: Int) {
  def hit: Boolean = (flags & 1) != 0
  /** A miss the arithmetic or a non-finite input flagged: pair mode writes it in compact mode too. */
  def flaggedMiss: Boolean = !hit && (flags & (RecordFlags.NONFINITE | RecordFlags.ARITH)) != 0
  /** What compact mode writes in pair mode. */
  def written: Boolean = hit || flaggedMiss
  override def toString: String =
    f"rec(pair=$pair flags=0x$flags%02x ${fields.map(f => f"0x$f%x").mkString(",")})"
}
object AfuRecord {
  def invalid(lay: BufferLayout, pair: Int) = AfuRecord(Seq.fill(lay.valueFields)(BigInt(0)), pair, 3 << 1)
  def word(line: BigInt, bit: Int, w: Int): BigInt = (line >> bit) & ((BigInt(1) << w) - 1)
  /** The record in `slot`; masked layouts carry no pair index, so `pair` names it. */
  def decode(line: BigInt, slot: Int, lay: BufferLayout, pair: Int = -1): AfuRecord = {
    val w = lay.linkWidth
    val b = slot * lay.recordBytes * 8
    val fields = (0 until lay.valueFields).map(i => word(line, b + i * w, w))
    val p = lay.pairIndexBit.map(i => word(line, b + i, 24).toInt).getOrElse(pair)
    AfuRecord(fields, p, word(line, b + lay.flagsBit, 8).toInt)
  }
  /** A mask header: (first pair, hit mask). */
  def header(line: BigInt, slot: Int, lay: BufferLayout): (Int, Int) = {
    val b = slot * lay.recordBytes * 8
    (word(line, b + MaskHeader.PAIR_SHIFT, MaskHeader.PAIR_BITS).toInt, word(line, b + MaskHeader.MASK_SHIFT, MaskHeader.MASK_BITS).toInt)
  }
  /** Whether a line is zero from record slot `slot` to its end (unused slots and padding). */
  def zeroFrom(line: BigInt, slot: Int, lay: BufferLayout): Boolean = (line >> (slot * lay.recordBytes * 8)) == 0
}

/** A run's input: spheres as link words (x, y, z, r), pairs of indices, the mode and the
  * contact buffer's capacity (None: room for every record); `lanes`, the AFU's group size
  * (min(SCPUs, 16)), tells where masked layouts put their headers. */
final case class World(lay: BufferLayout, spheres: IndexedSeq[Seq[BigInt]], pairs: IndexedSeq[(Int, Int)],
                       dense: Boolean, capacity: Option[Long] = None, numSpheres: Option[Long] = None,
                       lanes: Int = 16) {
  def w: Int = lay.linkWidth
  def nSpheres: Long = numSpheres.getOrElse(spheres.size.toLong)
  def bad(k: Int): Boolean = pairs(k)._1 >= nSpheres || pairs(k)._2 >= nSpheres
  /** The groups the dispatcher cuts the pairs into: up to `lanes` consecutive pairs of one line. */
  def groups: Seq[Range] = (0 until pairs.size by lay.pairsPerLine).flatMap { l =>
    val end = math.min(l + lay.pairsPerLine, pairs.size)
    (l until end by lanes).map(g => g until math.min(g + lanes, end))
  }
}

/** The status line, decoded. */
final case class Status(words: IndexedSeq[Long]) {
  private def f(off: Int) = words(off / 4)
  def done = f(StatusLine.DONE); def errors = f(StatusLine.ERROR_FLAGS)
  def processed = f(StatusLine.PAIRS_PROCESSED); def found = f(StatusLine.CONTACTS_FOUND)
  def written = f(StatusLine.RECORDS_WRITTEN); def nonFinite = f(StatusLine.NONFINITE_PAIRS)
  def firstBad = f(StatusLine.FIRST_BAD_PAIR); def flaggedMisses = f(StatusLine.FLAGGED_MISSES)
  def cycles = f(StatusLine.CYCLES_TOTAL)
  def cycLoad = f(StatusLine.CYCLES_LOAD); def cycCompute = f(StatusLine.CYCLES_COMPUTE)
  def cycWaitRd = f(StatusLine.CYCLES_WAIT_RD); def cycWaitWr = f(StatusLine.CYCLES_WAIT_WR)
  override def toString = s"Status(done=$done err=0x${errors.toHexString} processed=$processed found=$found " +
    s"written=$written nonFinite=$nonFinite firstBad=$firstBad flaggedMisses=$flaggedMisses cycles=$cycles load=$cycLoad compute=$cycCompute " +
    s"waitRd=$cycWaitRd waitWr=$cycWaitWr)"
}
object Status {
  def apply(line: BigInt): Status = Status((0 until 16).map(i => ((line >> (32 * i)) & 0xFFFFFFFFL).toLong))
}

final case class RunResult(status: Option[Status], writes: Seq[WriteEvent], cycles: Long,
                           contactBase: BigInt, statusAddr: BigInt)

/** Puts a world into host memory, programs the CSRs, starts the AFU and runs the link until
  * the status line is written and every response has returned. */
object AfuRun {
  val sphereBase  = BigInt(0x1000)
  val pairBase    = BigInt(0x20000)
  val contactBase = BigInt(0x80000)
  val statusAddr  = BigInt(0x7fff0)

  /** A sphere table and a pair list in host memory, in lines at the given line addresses, as
    * the host lays them out. */
  def writeLines(mem: HostMemoryModel, lay: BufferLayout, spheres: Seq[Seq[BigInt]], pairs: Seq[(Int, Int)],
                 spheresAt: BigInt, pairsAt: BigInt): Unit = {
    val w = lay.linkWidth
    spheres.grouped(lay.spheresPerLine).zipWithIndex.foreach { case (group, l) =>
      mem.mem(spheresAt + l) = group.zipWithIndex.map { case (s, k) =>
        s.zipWithIndex.map { case (v, c) => v << (k * 4 * w + c * w) }.sum
      }.sum
    }
    pairs.grouped(lay.pairsPerLine).zipWithIndex.foreach { case (group, l) =>
      mem.mem(pairsAt + l) = group.zipWithIndex.map { case ((i, j), k) =>
        (BigInt(i & 0xffff) << (32 * k)) | (BigInt(j & 0xffff) << (32 * k + 16)) }.sum
    }
  }

  def run(mem: HostMemoryModel, world: World, maxCycles: Long = -1,
          csrOverride: Map[Int, BigInt] = Map.empty): RunResult = {
    writeLines(mem, world.lay, world.spheres, world.pairs, sphereBase, pairBase)
    val cap = world.capacity.getOrElse(world.lay.compactSlotsFor(world.pairs.size.toLong) + 3)
    val csrs = Map[Int, BigInt](Csr.SPHERE_BASE -> sphereBase, Csr.NUM_SPHERES -> world.nSpheres,
      Csr.PAIR_BASE -> pairBase, Csr.NUM_PAIRS -> world.pairs.size, Csr.CONTACT_BASE -> contactBase,
      Csr.CONTACT_CAPACITY -> cap, Csr.STATUS_ADDR -> statusAddr, Csr.MODE -> (if (world.dense) 1 else 0)) ++ csrOverride
    csrs.toSeq.sortBy(_._1).foreach { case (i, v) => mem.writeCsr(i, v) }
    val first = mem.writes.size
    val startCycle = mem.cycle
    mem.writeCsr(Csr.CTRL, Csr.CTRL_START)
    val sa = csrs(Csr.STATUS_ADDR)
    val limit = if (maxCycles > 0) maxCycles else 20000L + 400L * world.pairs.size
    var seenAt = -1L // the cycle the status line was written (counted in cycles, so skipping changes nothing)
    while (!(seenAt >= 0 && mem.idleLink() && mem.cycle - seenAt > 8) && mem.cycle - startCycle < limit) {
      mem.step()
      if (seenAt < 0 && mem.writes.drop(first).exists(_.addr == sa)) seenAt = mem.cycle
    }
    val ws = mem.writes.drop(first).toSeq
    RunResult(ws.find(_.addr == sa).map(e => Status(e.data)), ws, mem.cycle - startCycle, csrs(Csr.CONTACT_BASE), sa)
  }

  /** Checks one run against the expected record of every pair; returns failures (empty = ok). */
  def check(world: World, expect: Int => AfuRecord, r: RunResult, expectErrors: Long = -1): Seq[String] = {
    val lay = world.lay; val R = lay.recordsPerLine
    val errs = scala.collection.mutable.ArrayBuffer[String]()
    def fail(s: String) = errs += s
    val n = world.pairs.size
    val exp = (0 until n).map(k => if (world.bad(k)) AfuRecord.invalid(lay, k) else expect(k))
    val hits = exp.filter(_.hit)
    val recorded = exp.filter(_.written) // compact mode's records: hits and flagged misses
    val cap = world.capacity.getOrElse(lay.compactSlotsFor(n.toLong) + 3)
    // masked compact: a header before the records of each group with one
    val recordGroups = world.groups.filter(_.exists(k => exp(k).written))
    val masked = lay.masked && !world.dense
    r.status match {
      case None => fail(s"no status line written in ${r.cycles} cycles"); return errs.toSeq
      case Some(st) =>
        val statusWrites = r.writes.filter(_.addr == r.statusAddr)
        if (statusWrites.size != 1) fail(s"status line written ${statusWrites.size} times")
        val sw = statusWrites.head
        if (r.writes.last != sw) fail("status line is not the last write")
        val before = r.writes.indexOf(sw)
        if (sw.respondedBefore < before) fail(s"status written with ${before - sw.respondedBefore} contact writes unacknowledged")
        val contactLines = lay.contactBufferLines(cap, world.dense)
        for (e <- r.writes if e.addr != r.statusAddr)
          if (e.addr < r.contactBase || e.addr >= r.contactBase + contactLines)
            fail(s"write outside the buffers: line 0x${e.addr.toString(16)}")
        val lines = r.writes.filter(_.addr != r.statusAddr)
        if (lines.map(_.addr).distinct.size != lines.size) fail("a contact line written twice")
        val total = if (world.dense) n.toLong else recorded.size.toLong + (if (masked) recordGroups.size else 0)
        val written = math.min(total, cap)
        val nonFin = exp.count(e => (e.flags & RecordFlags.NONFINITE) != 0)
        val firstBad = (0 until n).find(world.bad).map(_.toLong).getOrElse(StatusLine.NO_BAD_PAIR)
        val expErr = if (expectErrors >= 0) expectErrors else
          (if (firstBad != StatusLine.NO_BAD_PAIR) ErrorFlags.INDEX_RANGE else 0) |
          (if (total > cap) ErrorFlags.CAPACITY else 0) | (if (nonFin > 0) ErrorFlags.NONFINITE else 0)
        if (st.done != 1) fail(s"done = ${st.done}")
        if (st.errors != expErr) fail(s"error flags 0x${st.errors.toHexString}, expected 0x${expErr.toHexString}")
        if ((expErr & (ErrorFlags.BAD_CONFIG | ErrorFlags.TOO_MANY_SPHERES)) != 0) {
          if (lines.nonEmpty) fail(s"${lines.size} contact lines written despite error 0x${expErr.toHexString}")
          if (st.processed != 0 || st.written != 0) fail(s"counters not zero: $st")
          return errs.toSeq
        }
        if (st.processed != n) fail(s"pairs processed ${st.processed}, expected $n")
        if (st.found != hits.size) fail(s"contacts found ${st.found}, expected ${hits.size}")
        if (st.written != written) fail(s"records written ${st.written}, expected $written")
        if (st.nonFinite != nonFin) fail(s"non-finite pairs ${st.nonFinite}, expected $nonFin")
        if (st.flaggedMisses != exp.count(_.flaggedMiss)) fail(s"flagged misses ${st.flaggedMisses}, expected ${exp.count(_.flaggedMiss)}")
        if (st.firstBad != firstBad) fail(s"first bad pair ${st.firstBad}, expected $firstBad")
        def place(rn: Long): (Long, Int) =
          if (world.dense) (lay.denseLine(rn), lay.denseSlot(rn)) else (rn / R, (rn % R).toInt)
        val wantLines = lay.contactBufferLines(written, world.dense)
        if (lines.size != wantLines) fail(s"${lines.size} contact lines written, expected $wantLines")
        val byAddr = lines.map(e => e.addr -> e.data).toMap
        val slotAt = (rn: Long) => { val (l, slot) = place(rn); (byAddr.getOrElse(r.contactBase + l, BigInt(0)), slot) }
        val recs: Seq[AfuRecord] = if (!masked) (0L until written).map { rn =>
          val (line, slot) = slotAt(rn); AfuRecord.decode(line, slot, lay, if (world.dense) rn.toInt else -1)
        } else {
          // header, its hits, the next header...: groups in the order pair lines arrived (any),
          // each once; the buffer may end inside a group
          val byFirst = recordGroups.map(g => g.head -> g).toMap
          val seen = scala.collection.mutable.Set[Int]()
          val out = scala.collection.mutable.ArrayBuffer[AfuRecord]()
          var rn = 0L
          while (rn < written) {
            val (line, slot) = slotAt(rn)
            val (first, mask) = AfuRecord.header(line, slot, lay)
            val rest = AfuRecord.word(line, slot * lay.recordBits, lay.recordBits) >> MaskHeader.BITS
            if (!byFirst.contains(first) || seen(first) || rest != 0) {
              fail(s"slot $rn: header (first $first, mask 0x${mask.toHexString}) names no group with a record, or one seen before")
              rn = written
            } else {
              seen += first
              val want = byFirst(first).filter(k => exp(k).written)
              val wantMask = want.map(k => 1 << (k - first)).sum
              if (mask != wantMask) fail(s"slot $rn: mask 0x${mask.toHexString}, expected 0x${wantMask.toHexString}")
              rn += 1
              for (k <- want if rn < written) { val (l2, s2) = slotAt(rn); out += AfuRecord.decode(l2, s2, lay, k); rn += 1 }
            }
          }
          out.toSeq
        }
        // slots holding no record, and every line's padding, are zero
        val used = (0L until written).map(place).groupBy(_._1).map { case (l, ss) => l -> ss.map(_._2).toSet }
        for (e <- lines; l = (e.addr - r.contactBase).toLong; slot <- 0 until R if !used.getOrElse(l, Set.empty[Int]).contains(slot))
          if (AfuRecord.word(e.data, slot * lay.recordBytes * 8, lay.recordBytes * 8) != 0) fail(s"line $l slot $slot: not zero")
        for (e <- lines if !AfuRecord.zeroFrom(e.data, R, lay)) fail(s"line ${e.addr - r.contactBase}: padding not zero")
        if (world.dense) {
          for (k <- 0 until written.toInt if recs(k) != exp(k))
            if (errs.size < 20) fail(s"dense record $k: got ${recs(k)}, expected ${exp(k)}")
        } else {
          val pairsSeen = recs.map(_.pair)
          if (pairsSeen.distinct.size != pairsSeen.size) fail("a pair has two records")
          for (rec <- recs) {
            if (rec.pair >= n || exp(rec.pair) != rec) { if (errs.size < 20) fail(s"compact record $rec, expected ${if (rec.pair < n) exp(rec.pair) else "none"}") }
          }
          if (written == total && pairsSeen.toSet != recorded.map(_.pair).toSet) fail("the set of recorded pairs (hits, flagged misses) differs")
        }
    }
    errs.toSeq
  }
}
