package collide.afu

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.testutil.Seeds

/** The PUC with stand-in compute units (StubScpu): ordering, accounting, errors and link
  * rules over many seeded worlds, on hostile and ideal links. */
class PucSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "Puc"

  def params(n: Int, w: Int, maxSpheres: Int = 256, reads: Int = 16, writes: Int = 8) =
    PucParams(scpus = n, linkWidth = w, scpuTagBits = 24, scpuLatency = 3, maxSpheres = maxSpheres,
      maxReads = reads, maxWrites = writes, tagBits = 6, name = s"_t$n")

  def randomWorld(rnd: scala.util.Random, w: Int, maxSpheres: Int, dense: Boolean, bad: Boolean): World = {
    val ns = 1 + rnd.nextInt(maxSpheres)
    val spheres = (0 until ns).map { _ =>
      Seq.fill(4)(BigInt(w, rnd.self)).updated(3, if (rnd.nextInt(20) == 0) BigInt(0xff) << (w - 9) else BigInt(w, rnd.self))
    }
    val np = rnd.nextInt(4) match { case 0 => rnd.nextInt(5); case 1 => 1 + rnd.nextInt(40); case _ => 16 * (1 + rnd.nextInt(12)) + rnd.nextInt(3) }
    val pairs = (0 until np).map { _ =>
      def idx = if (bad && rnd.nextInt(25) == 0) ns + rnd.nextInt(70000 - ns) min 65535 else rnd.nextInt(ns)
      (idx, idx)
    }
    World(w, spheres, pairs, dense)
  }
  def stubExpect(world: World)(k: Int): AfuRecord =
    StubScpu.model(world.w, world.spheres(world.pairs(k)._1), world.spheres(world.pairs(k)._2), k)

  def soak(n: Int, w: Int, worlds: Int, beh: Seq[LinkBehaviour], anno: Seq[firrtl2.annotations.Annotation] = Seq()): Unit = {
    val p = params(n, w)
    val rnd = Seeds.rng(s"PucSpec-n$n-w$w")
    test(new PucHarness(p, 3)).withAnnotations(anno) { dut =>
      dut.clock.setTimeout(0)
      for (i <- 0 until worlds) {
        val b = beh(i % beh.size)
        val mem = new HostMemoryModel(dut.io, dut.clock, b, rnd.nextLong(), p.maxReads, p.maxWrites)
        val world = randomWorld(rnd, w, p.maxSpheres, dense = rnd.nextBoolean(), bad = rnd.nextInt(3) == 0)
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
}
