package collide.world

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.testutil.{Builds, Seeds}
import collide.world.model.BroadPhaseModel

class BucketSortSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "BucketSort"

  private val maxItems = 256
  private val bucketsLog2 = 7
  // On Verilator: treadle took minutes for the two-port sorts' counter memories.
  private def verilator(design: String) = Builds.verilator("BucketSortSpec", design)

  private def waitIdle(dut: BucketSort): Unit = {
    var n = 0
    while (dut.io.busy.peek().litToBoolean) { dut.clock.step(); n += 1; assert(n < 10000, "busy forever") }
  }

  private def pulse(dut: BucketSort, sig: Bool): Unit = {
    sig.poke(true.B); dut.clock.step(); sig.poke(false.B); dut.clock.step(); waitIdle(dut)
  }

  /** Streams the items, port p taking the p-th part of them (halves with two ports, as the
    * broad phase splits the table), each port with idle cycles of its own between items. */
  private def stream(dut: BucketSort, rng: scala.util.Random, items: Seq[(Int, Int)], scatter: Boolean): Unit = {
    val ports = dut.io.in.length
    val half = items.length / 2
    val parts = if (ports == 1) Array(items) else Array(items.take(half), items.drop(half))
    while (parts.exists(_.nonEmpty)) {
      for ((in, p) <- dut.io.in.zipWithIndex) {
        val go = parts(p).nonEmpty && rng.nextInt(4) != 0
        in.valid.poke(go.B)
        if (go) {
          val (item, b) = parts(p).head; parts(p) = parts(p).tail
          in.bits.scatter.poke(scatter.B); in.bits.bucket.poke(b.U); in.bits.item.poke(item.U)
          assert(in.ready.peek().litToBoolean, "not ready while idle")
        }
      }
      dut.clock.step()
    }
    dut.io.in.foreach(_.valid.poke(false.B)); dut.clock.step()
  }

  /** `walk`: the buckets the prefix sum covers (all in use by default); the lookups below it are checked. */
  /** With clearBehind (`dut.io.scrub`), the cursors are cleared behind the scatter while the
    * lookups, entries and marks below are checked; `hurry`: the next world's clear is asked
    * while that clearing may still run (it must wait for it), else once it is over (it must
    * then cost no cycle). Returns the cycles the clear kept the sort busy. */
  private def sortWorld(dut: BucketSort, rng: scala.util.Random, label: String, items: Seq[(Int, Int)], usedLog2: Int,
                        walk: Option[Int] = None, hurry: Boolean = false): Int = {
    val walked = walk.getOrElse(1 << usedLog2)
    dut.io.usedLog2.poke(usedLog2.U)
    dut.io.walkBuckets.poke(walked.U)
    dut.io.clear.poke(true.B); dut.clock.step(); dut.io.clear.poke(false.B)
    var clearBusy = 0
    while (dut.io.busy.peek().litToBoolean) { dut.clock.step(); clearBusy += 1; assert(clearBusy < 10000, "busy forever") }
    dut.clock.step()
    stream(dut, rng, items, scatter = false)
    pulse(dut, dut.io.prefix)
    stream(dut, rng, items, scatter = true)
    for (scrub <- dut.io.scrub) {
      scrub.poke(true.B); dut.clock.step(); scrub.poke(false.B)
      assert(dut.io.busy.peek().litToBoolean, s"$label: not clearing behind the scatter")
      if (hurry) return clearBusy
    }
    assert(dut.io.counted.peek().litValue == items.length && dut.io.scattered.peek().litValue == items.length, label)
    assert(!dut.io.badBucket.peek().litToBoolean, label)
    val (start, entries) = BroadPhaseModel.countingSort(items, 1 << usedLog2)
    val copies = dut.io.lookup.indices
    for (b <- 0 until walked) {
      dut.io.lookup.foreach(_.bucket.poke(b.U)); dut.clock.step()
      for (c <- copies; lk = dut.io.lookup(c))
        assert(lk.begin.peek().litValue == start(b) && lk.end.peek().litValue == start(b + 1),
          s"$label: copy $c's bucket $b is [${lk.begin.peek().litValue}, ${lk.end.peek().litValue}), want [${start(b)}, ${start(b + 1)})")
    }
    for (a <- entries.indices) {
      dut.io.entry.foreach(_.addr.poke(a.U)); dut.clock.step()
      for (c <- copies) {
        assert(dut.io.entry(c).item.peek().litValue == entries(a), s"$label: copy $c's entry $a")
        // The previous world marked some of these positions: the scatter cleared them.
        assert(!dut.io.entry(c).mark.peek().litToBoolean, s"$label: copy $c's entry $a is marked after the scatter")
      }
    }
    // Mark about half the entries of each copy, each its own (as the candidate generators
    // do), then read them back.
    val marked = copies.map(_ => entries.indices.filter(_ => rng.nextBoolean()).toSet)
    for (a <- entries.indices) {
      for (c <- copies; m = dut.io.mark(c)) {
        m.valid.poke(marked(c)(a).B); m.bits.addr.poke(a.U); m.bits.item.poke(entries(a).U)
      }
      dut.clock.step()
    }
    dut.io.mark.foreach(_.valid.poke(false.B))
    for (a <- entries.indices) {
      dut.io.entry.foreach(_.addr.poke(a.U)); dut.clock.step()
      for (c <- copies)
        assert(dut.io.entry(c).item.peek().litValue == entries(a) && dut.io.entry(c).mark.peek().litToBoolean == marked(c)(a),
          s"$label: copy $c's entry $a after marking")
    }
    if (dut.io.scrub.isDefined) waitIdle(dut)
    clearBusy
  }

  // Counters one to a word (wordLog2 0) and eight to a word (the default: clear and prefix a
  // word a cycle); one port and one copy, and two ports (each scattering into its own share
  // of every bucket) with several copies.
  for ((wordLog2, copies, ports) <- Seq((3, 1, 1), (0, 1, 1), (3, 3, 2), (0, 2, 2), (4, 2, 2)))
  it should s"sort like the golden model with ${1 << wordLog2} counters a word, $copies copies and $ports ports: repeated buckets back to back, gaps, empty and full worlds, one after another, each scatter clearing the marks of the last" in {
    val rng = Seeds.rng(s"BucketSortSpec-w$wordLog2-c$copies-p$ports")
    test(new BucketSort(maxItems, bucketsLog2, wordLog2, copies, ports)).withAnnotations(verilator(s"w$wordLog2-c$copies-p$ports")) { dut =>
      dut.clock.setTimeout(0)
      val worlds = Seq(
        ("empty", Seq.empty[Int], 3),
        ("one item", Seq(5), 3),
        ("all in one bucket", Seq.fill(40)(2), 2),
        ("runs of repeats", Seq.fill(60)(rng.nextInt(4)).flatMap(b => Seq.fill(1 + rng.nextInt(3))(b)), 2),
        ("random, every bucket", Seq.fill(200)(rng.nextInt(1 << bucketsLog2)), bucketsLog2),
        ("full table", Seq.fill(maxItems)(rng.nextInt(16)), 4),
        ("fewer buckets after more", Seq.fill(30)(rng.nextInt(2)), 1)
      ) ++ Seq.tabulate(Seeds.cases(6))(i => (s"random $i", Seq.fill(rng.nextInt(maxItems + 1))(rng.nextInt(32)), 5))
      // The prefix sum over the first two words alone (box buckets' walk) after the first
      // worlds, and full ones after it: the buckets below it are as with every word summed.
      val walk = math.min(1 << bucketsLog2, 2 << wordLog2)
      val low = Seq.fill(rng.nextInt(maxItems + 1))(rng.nextInt(walk))
      for ((label, bs, usedLog2, walked) <- worlds.take(4).map(w => (w._1, w._2, w._3, None)) ++
             Seq((s"a walk of $walk buckets", low, bucketsLog2, Some(walk))) ++ worlds.drop(4).map(w => (w._1, w._2, w._3, None))) {
        val items = bs.map(_ % (1 << usedLog2)).zipWithIndex.map { case (b, i) => (i, b) }
        sortWorld(dut, rng, label, items, usedLog2, walked)
      }
    }
  }

  for ((wordLog2, copies, ports) <- Seq((3, 2, 1), (2, 3, 2)))
  it should s"clear its counters behind the scatter while the lookups serve the world ($copies copies, $ports ports), so that the next world's clear costs no cycle, and one asked early waits for it" in {
    val rng = Seeds.rng(s"BucketSortSpec-behind-w$wordLog2-c$copies-p$ports")
    test(new BucketSort(maxItems, bucketsLog2, wordLog2, copies, ports, clearBehind = true)).withAnnotations(verilator(s"behind-w$wordLog2-c$copies-p$ports")) { dut =>
      dut.clock.setTimeout(0)
      val words = (1 << bucketsLog2) >> wordLog2
      var lastHurried = false // the world before asked its clear while the clearing behind ran
      for (k <- 0 until Seeds.cases(12)) {
        val usedLog2 = 1 + rng.nextInt(bucketsLog2)
        val items = Seq.fill(rng.nextInt(maxItems + 1))(rng.nextInt(1 << usedLog2)).zipWithIndex.map { case (b, i) => (i, b) }
        // A walk shorter than the buckets in use (box buckets), a whole number of words: the
        // broad phase never walks more buckets than it uses.
        val walk = if (usedLog2 > wordLog2 && rng.nextInt(3) == 0) Some(((1 << usedLog2) / 2) >> wordLog2 << wordLog2) else None
        val hurry = rng.nextInt(3) == 0
        val busy = sortWorld(dut, rng, s"world $k (${items.size} items, 2^$usedLog2 buckets${if (hurry) ", cleared early" else ""})",
          items.map { case (i, b) => (i, walk.fold(b)(w => b % w)) }, usedLog2, walk, hurry)
        // After reset every word is cleared; after a finished clear behind, nothing is left to do.
        if (k == 0) assert(busy == words, s"the first clear took $busy cycles, want every word ($words)")
        else if (!lastHurried) assert(busy == 0, s"world $k: the clear took $busy cycles after the clear behind was over")
        lastHurried = hurry
      }
    }
  }

  it should "hold items wider than its positions, as a group of a four-port sort holds its half of a larger table" in {
    val rng = Seeds.rng("BucketSortSpec-wide-items")
    // Positions 0..127, items 9 bits: the second half of a 512-sphere table's indices.
    test(new BucketSort(128, bucketsLog2, 4, 2, 2, itemBits = 9)).withAnnotations(verilator("wide-items")) { dut =>
      dut.clock.setTimeout(0)
      for ((label, n, usedLog2) <- Seq(("full half", 128, 5), ("part", 77, bucketsLog2), ("one", 1, 2))) {
        val items = Seq.tabulate(n)(i => (300 + i, rng.nextInt(1 << usedLog2)))
        sortWorld(dut, rng, label, items, usedLog2)
      }
    }
  }

  it should "refuse a bucket outside the used range and say so, without writing it" in {
    test(new BucketSort(maxItems, bucketsLog2)) { dut =>
      dut.io.usedLog2.poke(2.U)
      pulse(dut, dut.io.clear)
      val rng = new scala.util.Random(1)
      stream(dut, rng, Seq((0, 1), (1, 9)), scatter = false) // 9 >= 4 buckets
      assert(dut.io.badBucket.peek().litToBoolean)
      assert(dut.io.counted.peek().litValue == 1)
      pulse(dut, dut.io.clear) // a new world forgets it
      assert(!dut.io.badBucket.peek().litToBoolean)
    }
  }
}
