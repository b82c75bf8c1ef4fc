package collide.afu

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.testutil.Seeds

/** The PUC with stand-in compute units (StubScpu): ordering, accounting, errors and link
  * rules over many seeded worlds, on hostile and ideal links. */
class PucSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "Puc"

  def params(n: Int, w: Int, maxSpheres: Int = 256, reads: Int = 16, writes: Int = 8,
             records: RecordLayout = RecordLayout.Full, ram: SphereRamPorts = SphereRamPorts.Replicated) =
    PucParams(scpus = n, linkWidth = w, scpuTagBits = 24, scpuLatency = 3, maxSpheres = maxSpheres,
      maxReads = reads, maxWrites = writes, tagBits = 6, records = records, ramPorts = ram,
      name = s"_t${n}_w${w}_${records.name}" + (if (ram == SphereRamPorts.Replicated) "" else s"_${ram.name}"))

  def randomWorld(rnd: scala.util.Random, lay: BufferLayout, maxSpheres: Int, dense: Boolean, bad: Boolean, lanes: Int): World = {
    val w = lay.linkWidth
    val ns = 1 + rnd.nextInt(maxSpheres)
    val spheres = (0 until ns).map { _ =>
      Seq.fill(4)(BigInt(w, rnd.self)).updated(3, if (rnd.nextInt(20) == 0) BigInt(0xff) << (w - 9) else BigInt(w, rnd.self))
    }
    val np = rnd.nextInt(4) match { case 0 => rnd.nextInt(5); case 1 => 1 + rnd.nextInt(40); case _ => 16 * (1 + rnd.nextInt(12)) + rnd.nextInt(3) }
    val pairs = (0 until np).map { _ =>
      def idx = if (bad && rnd.nextInt(25) == 0) ns + rnd.nextInt(70000 - ns) min 65535 else rnd.nextInt(ns)
      (idx, idx)
    }
    World(lay, spheres, pairs, dense, lanes = lanes)
  }
  def stubExpect(world: World)(k: Int): AfuRecord =
    StubScpu.model(world.lay, world.spheres(world.pairs(k)._1), world.spheres(world.pairs(k)._2), k)

  def soak(n: Int, w: Int, worlds: Int, beh: Seq[LinkBehaviour], anno: Seq[firrtl2.annotations.Annotation] = Seq(),
           records: RecordLayout = RecordLayout.Full, ram: SphereRamPorts = SphereRamPorts.Replicated): Unit = {
    val p = params(n, w, records = records, ram = ram)
    val rnd = Seeds.rng(s"PucSpec-n$n-w$w-${records.name}" + (if (ram == SphereRamPorts.Replicated) "" else s"-${ram.name}"))
    test(new PucHarness(p, 3)).withAnnotations(anno) { dut =>
      dut.clock.setTimeout(0)
      for (i <- 0 until worlds) {
        val b = beh(i % beh.size)
        val mem = new HostMemoryModel(dut.io, dut.clock, b, rnd.nextLong(), p.maxReads, p.maxWrites)
        val world = randomWorld(rnd, p.layout, p.maxSpheres, dense = rnd.nextBoolean(), bad = rnd.nextInt(3) == 0, p.lanes)
        val cap = if (rnd.nextInt(5) == 0) Some(rnd.nextInt(world.pairs.size + 2).toLong) else None
        val wc = world.copy(capacity = cap)
        val r = AfuRun.run(mem, wc)
        val errs = AfuRun.check(wc, stubExpect(wc), r)
        if (errs.nonEmpty) println(s"dbg: ${dut.dbg.map(_.peek().litValue)} pairs ${wc.pairs}")
        assert(errs.isEmpty, s"world $i (${b.name}, ${wc.pairs.size} pairs, ${wc.spheres.size} spheres, dense=${wc.dense}, cap=$cap): " +
          errs.mkString("; ") + s"\n${r.status}")
      }
    }
  }

  val verilator = Seq(chiseltest.simulator.VerilatorBackendAnnotation)
  it should "account for every pair with one SCPU on a hostile link (binary32)" in {
    soak(1, 32, Seeds.cases(12), Seq(LinkBehaviour.ideal, LinkBehaviour.hostile), verilator)
  }
  it should "account for every pair with three SCPUs (groups not dividing a line), binary64 link" in {
    soak(3, 64, Seeds.cases(12), Seq(LinkBehaviour.hostile, LinkBehaviour.ideal), verilator)
  }
  // Every record packing: (link width, layout) -> records a line 3 (16 full), 5 (32 derived),
  // 8 (16 derived), 3 (64 derived); 2 and 1 are the two cases above. Masked: 12 slots of
  // 5 bytes (a header fills its slot exactly), 7 of 9 with groups of 5 (5, 5, 5, 1 a line),
  // and 1 of 57.
  for ((w, lay, n) <- Seq((16, RecordLayout.Full, 2), (32, RecordLayout.Derived, 5), (16, RecordLayout.Derived, 4),
                         (64, RecordLayout.Derived, 3), (16, RecordLayout.DerivedMasked, 16),
                         (32, RecordLayout.DerivedMasked, 5), (64, RecordLayout.FullMasked, 3))) {
    val name = s"account for every pair with $n SCPUs, $w-bit link fields and ${lay.name} records (${BufferLayout(w, lay).recordsPerLine} a line)"
    def body(): Unit = soak(n, w, Seeds.cases(10), Seq(LinkBehaviour.hostile, LinkBehaviour.ideal), verilator, lay)
    // Sixteen SCPUs build the biggest model here (about 40 s): with SLOW=1; AfuSpec runs the
    // same packing with two fp16 SCPUs every time.
    if (n == 16) it should name taggedAs (collide.testutil.Slow) in body() else it should name in body()
  }

  it should "give identical writes, cycles and status lines when the host skips its idle cycles" in {
    val p = params(4, 32)
    val rnd = Seeds.rng("PucSpec-skip")
    test(new PucHarness(p, 3)).withAnnotations(verilator) { dut =>
      dut.clock.setTimeout(0)
      var skipped = 0L
      for (i <- 0 until Seeds.cases(8)) {
        val b = Seq(LinkBehaviour.harp, LinkBehaviour.hostile)(i % 2)
        val world = randomWorld(rnd, p.layout, p.maxSpheres, dense = rnd.nextBoolean(), bad = i % 3 == 2, p.lanes)
        val seed = rnd.nextLong()
        def once(skip: Boolean): (RunResult, Long) = {
          dut.reset.poke(true.B); dut.clock.step(); dut.reset.poke(false.B)
          val mem = new HostMemoryModel(dut.io, dut.clock, b, seed, p.maxReads, p.maxWrites, skipIdle = skip)
          (AfuRun.run(mem, world), mem.cyclesSkipped)
        }
        val (stepped, none) = once(skip = false)
        val (jumped, n) = once(skip = true)
        assert(none == 0)
        assert(AfuRun.check(world, stubExpect(world), jumped).isEmpty)
        assert(jumped.status == stepped.status, s"world $i (${b.name}): status differs")
        assert(jumped.writes == stepped.writes, s"world $i (${b.name}): writes differ (cycle, address or data)")
        assert(jumped.cycles == stepped.cycles)
        skipped += n
        println(f"[PucSpec] skip world $i (${b.name}, ${world.pairs.size} pairs): ${stepped.cycles} cycles, $n skipped")
      }
      assert(skipped > 0, "nothing was ever skipped: io.idle never held")
    }
  }

  it should "flag and contain every kind of bad input (index range, table size, capacity, non-finite, configuration)" in {
    val p = params(4, 32)
    val rnd = Seeds.rng("PucSpec-errors")
    test(new PucHarness(p, 3)).withAnnotations(verilator) { dut =>
      dut.clock.setTimeout(0)
      def mem() = new HostMemoryModel(dut.io, dut.clock, LinkBehaviour.hostile, rnd.nextLong(), p.maxReads, p.maxWrites)
      val spheres = (0 until 40).map(_ => Seq.fill(4)(BigInt(32, rnd.self)))
      val pairs = (0 until 37).map(_ => (rnd.nextInt(40), rnd.nextInt(40)))
      val base = World(p.layout, spheres, pairs, dense = false, lanes = p.lanes)
      def go(w: World, expectErr: Long = -1, csr: Map[Int, BigInt] = Map.empty): RunResult = {
        val r = AfuRun.run(mem(), w, csrOverride = csr)
        val errs = AfuRun.check(w, stubExpect(w), r, expectErr)
        assert(errs.isEmpty, s"$w: ${errs.mkString("; ")}\n${r.status}")
        r
      }
      // out-of-range indices: no contact, kind 3 in dense mode, the lowest bad pair reported
      val bad = base.copy(pairs = pairs.updated(20, (40, 3)).updated(9, (2, 65535)).updated(30, (1000, 1000)))
      for (d <- Seq(false, true)) {
        val r = go(bad.copy(dense = d))
        assert(r.status.get.firstBad == 9 && (r.status.get.errors & ErrorFlags.INDEX_RANGE) != 0)
      }
      // NUM_SPHERES above the table: nothing computed, nothing written but the status line
      val big = go(base.copy(numSpheres = Some(p.maxSpheres + 1L)), ErrorFlags.TOO_MANY_SPHERES)
      assert(big.writes.size == 1)
      // a contact buffer too small: records stop at the capacity, found counts them all
      for (d <- Seq(false, true); cap <- Seq(0L, 1L, 2L, 7L)) go(base.copy(dense = d, capacity = Some(cap)))
      // non-finite inputs (the stub reads r1 with an all-ones exponent as non-finite): counted
      val nf = base.copy(spheres = spheres.updated(5, spheres(5).updated(3, BigInt(0x7f800000L))), pairs = pairs.updated(0, (5, 6)))
      assert(go(nf).status.get.nonFinite >= 1)
      // bad configuration: status only, error bit 4
      go(base, ErrorFlags.BAD_CONFIG, Map(Csr.PAIR_BASE -> 0))
      go(base, ErrorFlags.BAD_CONFIG, Map(Csr.NUM_PAIRS -> (BigInt(1) << 24)))
      go(base, ErrorFlags.BAD_CONFIG, Map(Csr.CONTACT_BASE -> 0))
      go(base, ErrorFlags.BAD_CONFIG, Map(Csr.MODE -> Csr.MODE_WORLD)) // world mode is not built here
      // no status address: nothing can be reported, nothing is written, the next run works
      val silent = AfuRun.run(mem(), base, maxCycles = 300, csrOverride = Map(Csr.STATUS_ADDR -> 0))
      assert(silent.writes.isEmpty && silent.status.isEmpty)
      go(base.copy(dense = true))
    }
  }

  def rate(n: Int): Unit = {
    {
      val p = params(n, 32, reads = 64, writes = 64)
      val rnd = Seeds.rng(s"PucSpec-rate-$n")
      test(new PucHarness(p, 3)).withAnnotations(verilator) { dut =>
        dut.clock.setTimeout(0)
        val spheres = (0 until 256).map(_ => Seq.fill(4)(BigInt(32, rnd.self)))
        for (dense <- Seq(false, true)) {
          val w = World(p.layout, spheres, (0 until 16 * 120).map(_ => (rnd.nextInt(256), rnd.nextInt(256))), dense)
          val r = AfuRun.run(new HostMemoryModel(dut.io, dut.clock, LinkBehaviour.ideal, rnd.nextLong(), 64, 64), w)
          val errs = AfuRun.check(w, stubExpect(w), r)
          assert(errs.isEmpty, errs.mkString("; "))
          val st = r.status.get
          println(s"[PucSpec] n=$n dense=$dense: ${w.pairs.size} pairs in ${st.cycles} cycles, compute ${st.cycCompute}; $st")
          // a group (a whole line) a cycle: 120 compute cycles. Compact: the stub hits ~30% (~5 hits a
          // line, ~2.5 record lines a pair line), so writes bound the run; dense: 8 record lines a pair line.
          assert(st.cycCompute == 120, s"not a line a cycle: $st")
          if (!dense) assert(st.cycles < 120 * 4 + 200, s"too slow: $st")
        }
      }
    }
  }

  it should "dispatch a line a cycle with sixteen SCPUs on an ideal link" in { rate(16) }

  // Banked sphere table: every pair accounted for under bank conflicts; 4 banks for 4 SCPUs
  // (eight reads a cycle into eight ports) conflict most.
  for ((n, w, ram) <- Seq((4, 32, SphereRamPorts.Banked(Some(4))), (3, 64, SphereRamPorts.Banked()),
                          (2, 16, SphereRamPorts.Banked()))) {
    val p = params(n, w, ram = ram)
    it should s"account for every pair with $n SCPUs reading a table in ${p.banks} banks ($w-bit link fields)" in {
      soak(n, w, Seeds.cases(10), Seq(LinkBehaviour.hostile, LinkBehaviour.ideal), verilator, ram = ram)
    }
  }

  it should "cut a group only where a bank of the table would get a third sphere in a cycle" in {
    val p = params(16, 32, reads = 64, writes = 64, ram = SphereRamPorts.Banked())
    assert(p.banks == 32 && p.ramCopies == 1)
    val rnd = Seeds.rng("PucSpec-banked-rate")
    test(new PucHarness(p, 3)).withAnnotations(verilator) { dut =>
      dut.clock.setTimeout(0)
      val spheres = (0 until 256).map(_ => Seq.fill(4)(BigInt(32, rnd.self)))
      val lines = 120
      def run(name: String, pair: Int => (Int, Int)): Long = {
        val w = World(p.layout, spheres, (0 until 16 * lines).map(pair), dense = true)
        val r = AfuRun.run(new HostMemoryModel(dut.io, dut.clock, LinkBehaviour.ideal, rnd.nextLong(), 64, 64), w)
        val errs = AfuRun.check(w, stubExpect(w), r)
        assert(errs.isEmpty, s"$name: " + errs.mkString("; "))
        val st = r.status.get
        println(s"[PucSpec] banked, $name: ${w.pairs.size} pairs in ${st.cycCompute} compute cycles")
        st.cycCompute
      }
      // The 32 reads of a line on 32 banks; two spheres of one bank in pair k: a line a cycle.
      assert(run("32 banks once", k => (2 * k % 256, (2 * k + 1) % 256)) == lines)
      assert(run("a bank's two spheres", k => (k % 16, k % 16 + 32 * (1 + k / 16 % 7))) == lines)
      // Reads of one sphere share its port: one sphere everywhere, one sphere in every pair of
      // a line (as in ODE's lists), two spheres of bank 0 taking turns: a line a cycle.
      assert(run("one sphere", _ => (7, 7)) == lines)
      assert(run("one sphere a line", k => (32 * (k / 16 % 8), 1 + 2 * (k % 16))) == lines)
      assert(run("two spheres of a bank in turn", k => (32 * (k % 2), 1 + 2 * (k % 15))) == lines)
      // Bank 0 gets a new sphere in every pair (sphere i), the other reads on odd banks: the
      // third sphere ends the group, two pairs a cycle.
      assert(run("bank 0 a new sphere a pair", k => (32 * (k % 8), 1 + 2 * (k % 15))) == 8 * lines)
      val random = run("random", _ => (rnd.nextInt(256), rnd.nextInt(256)))
      assert(random > lines && random < 16 * lines)
    }
  }
  it should "spread the work over all of 20 SCPUs" taggedAs (collide.testutil.Slow) in { rate(20) }
}
