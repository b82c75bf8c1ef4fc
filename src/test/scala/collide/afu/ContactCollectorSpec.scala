package collide.afu

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.FpFlags
import collide.scpu.ContactKind
import collide.testutil.{Builds, Seeds}

/** The ContactCollector alone against a Scala model of its record stream: groups of random
  * size and invalid pairs, SCPU results that arrive late and out of step, and a packer whose
  * room changes every cycle. The stream of records (and headers), in order, and the counters'
  * totals must be the model's, whatever the timing. */
class ContactCollectorSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "ContactCollector"

  case class Result(hit: Boolean, kind: Int, vals: Map[String, BigInt], nonFinite: Boolean, flags: Int, tag: BigInt)
  case class Group(base: Int, cnt: Int, invalid: Int, first: Int, results: Seq[Result])

  def params(n: Int, w: Int, records: RecordLayout) =
    PucParams(scpus = n, linkWidth = w, scpuTagBits = 24, scpuLatency = 3, maxSpheres = 256, maxReads = 16,
      maxWrites = 8, tagBits = 6, records = records, name = s"_c${n}_w${w}_${records.name}")

  private val fieldNames = Seq("px", "py", "pz", "nx", "ny", "nz", "depth", "d", "w")
  private val arithFlags = FpFlags.Overflow | FpFlags.Invalid

  /** The records a group writes, in order, as ContactCollector's doc and docs/afu-interface.md say. */
  def model(p: PucParams, g: Group, dense: Boolean, keepFlagged: Boolean): Seq[(BigInt, BigInt)] = {
    val lay = p.layout
    def pack(vals: Seq[BigInt], pair: BigInt, flags: Int): BigInt = {
      val v = vals.zipWithIndex.map { case (x, i) => x << (i * lay.linkWidth) }.foldLeft(BigInt(0))(_ | _)
      val top = lay.valueFields * lay.linkWidth
      if (lay.masked) v | (BigInt(flags) << top) else v | (pair << top) | (BigInt(flags) << (top + RecordTag.PAIR_BITS))
    }
    val recs = g.results.zipWithIndex.map { case (r, k) =>
      val inv = (g.invalid >> k & 1) == 1
      val pair = r.tag & ((BigInt(1) << RecordTag.PAIR_BITS) - 1)
      val arith = (r.flags & arithFlags) != 0
      val hit = !inv && r.hit
      val flagged = !inv && !r.hit && (r.nonFinite || arith)
      val bits =
        if (inv) pack(Seq.fill(lay.valueFields)(BigInt(0)), pair, ContactKind.Invalid << RecordFlags.KIND_SHIFT)
        else pack(lay.records.fields.map(r.vals), pair, (if (arith) RecordFlags.ARITH else 0) |
          (if (r.nonFinite) RecordFlags.NONFINITE else 0) | (r.kind << RecordFlags.KIND_SHIFT) | (if (r.hit) RecordFlags.HIT else 0))
      (hit || (keepFlagged && flagged), bits, pair)
    }
    if (dense) recs.map(r => (r._2, r._3))
    else {
      val kept = recs.filter(_._1).map(r => (r._2, r._3))
      val mask = recs.zipWithIndex.map { case (r, k) => if (r._1) 1 << k else 0 }.sum
      val header = (BigInt(mask) << MaskHeader.MASK_SHIFT) | (BigInt(g.first) << MaskHeader.PAIR_SHIFT)
      if (lay.masked && kept.nonEmpty) (header, BigInt(g.first)) +: kept else kept
    }
  }

  def soak(n: Int, w: Int, records: RecordLayout, groups: Int): Unit = {
    val p = params(n, w, records)
    val L = p.lanes
    val R = p.layout.recordsPerLine
    val rnd = Seeds.rng(s"ContactCollectorSpec-n$n-w$w-${records.name}")
    for (mode <- Seq((true, false), (false, true), (false, false))) {
      val (dense, keepFlagged) = mode
      var base = 0
      var first = 0
      val gs = (0 until groups).map { _ =>
        val cnt = rnd.nextInt(6) match { case 0 => rnd.nextInt(L + 1); case _ => L }
        val invalid = if (rnd.nextInt(4) == 0) rnd.nextInt(1 << cnt) else 0
        val rs = (0 until cnt).map { k =>
          val hit = rnd.nextInt(3) == 0
          Result(hit, if (hit) 1 + rnd.nextInt(2) else 0, fieldNames.map(_ -> BigInt(w, rnd.self)).toMap,
            rnd.nextInt(8) == 0, if (rnd.nextInt(6) == 0) rnd.nextInt(1 << FpFlags.width) else 0, BigInt(first + k))
        }
        val g = Group(base, cnt, invalid, first, rs)
        base = (base + cnt) % n; first += cnt
        g
      }
      val want = gs.flatMap(model(p, _, dense, keepFlagged))
      test(new ContactCollector(p)).withAnnotations(Builds.verilator("ContactCollectorSpec", s"n$n-w$w-${records.name}")) { c =>
        c.io.dense.poke(dense.B)
        c.io.keepFlagged.poke(keepFlagged.B)
        // Each SCPU's results in dispatch order, shown late at random; groups offered at random.
        val perScpu = Array.fill(n)(scala.collection.mutable.Queue[Result]())
        for (g <- gs; (r, k) <- g.results.zipWithIndex) perScpu((g.base + k) % n).enqueue(r)
        var gi = 0
        val got = scala.collection.mutable.ArrayBuffer[(BigInt, BigInt)]()
        var pairs, hits, nonFin, flagged, headers = BigInt(0)
        var cycles = 0
        while ((gi < gs.size || perScpu.exists(_.nonEmpty) || got.size < want.size || pairs < first) && cycles < 40 * groups + 200) {
          val offer = gi < gs.size && rnd.nextInt(4) != 0
          c.io.groups.valid.poke(offer.B)
          if (gi < gs.size) {
            val g = gs(gi)
            c.io.groups.bits.base.poke(g.base.U); c.io.groups.bits.cnt.poke(g.cnt.U)
            c.io.groups.bits.invalid.poke(g.invalid.U); c.io.groups.bits.first.poke(g.first.U)
          }
          val shown = (0 until n).map(s => perScpu(s).nonEmpty && rnd.nextInt(3) != 0)
          for (s <- 0 until n) {
            c.io.scpu(s).valid.poke(shown(s).B)
            if (perScpu(s).nonEmpty) {
              val r = perScpu(s).head
              val o = c.io.scpu(s).bits
              o.hit.poke(r.hit.B); o.kind.poke(r.kind.U); o.nonFinite.poke(r.nonFinite.B); o.flags.poke(r.flags.U)
              o.tag.poke(r.tag.U)
              o.px.poke(r.vals("px").U); o.py.poke(r.vals("py").U); o.pz.poke(r.vals("pz").U)
              o.nx.poke(r.vals("nx").U); o.ny.poke(r.vals("ny").U); o.nz.poke(r.vals("nz").U)
              o.depth.poke(r.vals("depth").U); o.d.poke(r.vals("d").U); o.nw.poke(r.vals("w").U)
            }
          }
          c.io.room.poke(rnd.nextInt(R + 1).U)
          val nr = c.io.nRecs.peek().litValue.toInt
          assert(nr <= c.io.room.peek().litValue, "more records than room")
          for (r <- 0 until nr) got += ((c.io.recs(r).bits.peek().litValue, c.io.recs(r).pair.peek().litValue))
          pairs += c.io.nPairs.peek().litValue; hits += c.io.nHits.peek().litValue
          nonFin += c.io.nNonFinite.peek().litValue; flagged += c.io.nFlagged.peek().litValue
          headers += (if (c.io.nHeaders.peek().litToBoolean) 1 else 0)
          if (offer && c.io.groups.ready.peek().litToBoolean) gi += 1
          for (s <- 0 until n) if (shown(s) && c.io.scpu(s).ready.peek().litToBoolean) perScpu(s).dequeue()
          c.clock.step()
          cycles += 1
        }
        val results = gs.flatMap(g => g.results.zipWithIndex.map { case (r, k) => (r, (g.invalid >> k & 1) == 1) })
        val what = s"dense=$dense keepFlagged=$keepFlagged"
        assert(got.size == want.size, s"$what: ${got.size} records, want ${want.size}")
        for (((g, x), i) <- got.zip(want).zipWithIndex)
          assert(g == x, s"$what: record $i is ${g._1.toString(16)} (pair ${g._2}), want ${x._1.toString(16)} (pair ${x._2})")
        assert(pairs == first, s"$what: $pairs pairs counted of $first")
        assert(hits == results.count { case (r, inv) => !inv && r.hit }, s"$what: hits")
        assert(nonFin == results.count { case (r, inv) => !inv && r.nonFinite }, s"$what: non-finite")
        assert(flagged == results.count { case (r, inv) => !inv && !r.hit && (r.nonFinite || (r.flags & arithFlags) != 0) },
          s"$what: flagged misses")
        val wantHeaders = if (p.layout.masked && !dense) gs.count(g => model(p, g, dense, keepFlagged).nonEmpty) else 0
        assert(headers == wantHeaders, s"$what: $headers headers, want $wantHeaders")
      }
    }
  }

  it should "write every record of full-record groups in order, whatever the SCPUs' and the packer's timing" in {
    soak(3, 32, RecordLayout.Full, Seeds.cases(40))
  }
  it should "put a masked group's header before its first record and none before a group without one" in {
    soak(5, 32, RecordLayout.DerivedMasked, Seeds.cases(40))
  }
  it should "keep the order when a group wraps round the SCPUs (four SCPUs, derived records on binary16)" in {
    soak(4, 16, RecordLayout.Derived, Seeds.cases(40))
  }
}
