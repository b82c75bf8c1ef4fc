package collide.world

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.testutil.Seeds
import collide.world.model.BroadPhaseModel

class BucketSortSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "BucketSort"

  private val maxItems = 256
  private val bucketsLog2 = 7

  private def waitIdle(dut: BucketSort): Unit = {
    var n = 0
    while (dut.io.busy.peek().litToBoolean) { dut.clock.step(); n += 1; assert(n < 10000, "busy forever") }
  }

  private def pulse(dut: BucketSort, sig: Bool): Unit = {
    sig.poke(true.B); dut.clock.step(); sig.poke(false.B); dut.clock.step(); waitIdle(dut)
  }

  /** Streams the items, with idle cycles between some of them. */
  private def stream(dut: BucketSort, rng: scala.util.Random, items: Seq[(Int, Int)], scatter: Boolean): Unit = {
    for ((item, b) <- items) {
      while (rng.nextInt(4) == 0) { dut.io.in.valid.poke(false.B); dut.clock.step() }
      dut.io.in.valid.poke(true.B)
      dut.io.in.bits.scatter.poke(scatter.B); dut.io.in.bits.bucket.poke(b.U); dut.io.in.bits.item.poke(item.U)
      assert(dut.io.in.ready.peek().litToBoolean, "not ready while idle")
      dut.clock.step()
    }
    dut.io.in.valid.poke(false.B); dut.clock.step()
  }

  private def sortWorld(dut: BucketSort, rng: scala.util.Random, label: String, items: Seq[(Int, Int)], usedLog2: Int): Unit = {
    dut.io.usedLog2.poke(usedLog2.U)
    pulse(dut, dut.io.clear)
    stream(dut, rng, items, scatter = false)
    pulse(dut, dut.io.prefix)
    stream(dut, rng, items, scatter = true)
    assert(dut.io.counted.peek().litValue == items.length && dut.io.scattered.peek().litValue == items.length, label)
    assert(!dut.io.badBucket.peek().litToBoolean, label)
    val (start, entries) = BroadPhaseModel.countingSort(items, 1 << usedLog2)
    for (b <- 0 until (1 << usedLog2)) {
      dut.io.lookup.bucket.poke(b.U); dut.clock.step()
      assert(dut.io.lookup.begin.peek().litValue == start(b) && dut.io.lookup.end.peek().litValue == start(b + 1),
        s"$label: bucket $b is [${dut.io.lookup.begin.peek().litValue}, ${dut.io.lookup.end.peek().litValue}), want [${start(b)}, ${start(b + 1)})")
    }
    for (a <- entries.indices) {
      dut.io.entry.addr.poke(a.U); dut.clock.step()
      assert(dut.io.entry.item.peek().litValue == entries(a), s"$label: entry $a")
      // The previous world marked some of these positions: the scatter cleared them.
      assert(!dut.io.entry.mark.peek().litToBoolean, s"$label: entry $a is marked after the scatter")
    }
    // Mark about half the entries (as the candidate generator does), then read them back.
    val marked = entries.indices.filter(_ => rng.nextBoolean()).toSet
    for (a <- marked) {
      dut.io.mark.valid.poke(true.B); dut.io.mark.bits.addr.poke(a.U); dut.io.mark.bits.item.poke(entries(a).U)
      dut.clock.step()
    }
    dut.io.mark.valid.poke(false.B)
    for (a <- entries.indices) {
      dut.io.entry.addr.poke(a.U); dut.clock.step()
      assert(dut.io.entry.item.peek().litValue == entries(a) && dut.io.entry.mark.peek().litToBoolean == marked(a),
        s"$label: entry $a after marking")
    }
  }

  // Counters one to a word (wordLog2 0) and eight to a word (the default: clear and prefix
  // a word a cycle).
  for (wordLog2 <- Seq(3, 0))
  it should s"sort like the golden model with ${1 << wordLog2} counters a word: repeated buckets back to back, gaps, empty and full worlds, one after another, each scatter clearing the marks of the last" in {
    val rng = Seeds.rng(s"BucketSortSpec-w$wordLog2")
    test(new BucketSort(maxItems, bucketsLog2, wordLog2)) { dut =>
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
      for ((label, bs, usedLog2) <- worlds) {
        val items = bs.map(_ % (1 << usedLog2)).zipWithIndex.map { case (b, i) => (i, b) }
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
