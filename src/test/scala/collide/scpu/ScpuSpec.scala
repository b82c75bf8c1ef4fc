package collide.scpu

import scala.util.Random
import chisel3._
import chiseltest._
import chiseltest.simulator.VerilatorBackendAnnotation
import chiseltest.internal.CachingAnnotation
import org.scalatest.flatspec.AnyFlatSpec
import collide.scpu.model._
import collide.testutil.{Seeds, Slow}

/** The SCPU RTL against its golden model, every preset, on Verilator (treadle needs minutes
  * per thousand cycles on a design this size). One ScpuBank holds all presets so one build
  * serves them; CachingAnnotation reuses it while the design is unchanged.
  */
class ScpuSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "Scpu"

  private val annos = Seq(VerilatorBackendAnnotation, CachingAnnotation)

  /** The hard cases, the conversion cases, and n random pairs: uniform, within a few ulps of
    * grazing, and large coordinates with small gaps (a third each), plus n/10 across the
    * whole exponent range and n/20 raw link-format patterns (specials, edges). */
  private def vectors(cfg: ScpuConfig, n: Int, rng: Random): (IndexedSeq[String], IndexedSeq[ScpuPair]) = {
    val v = new ScpuVectors(cfg)
    val all = v.hardCases ++ v.linkCases ++
      Seq.tabulate(n)(i => (i % 3) match {
        case 0 => s"uniform $i" -> v.uniform(rng)
        case 1 => s"grazing $i" -> v.grazing(rng)
        case _ => s"large coordinates, small gap $i" -> v.largeSmallGap(rng)
      }) ++
      Seq.tabulate(n / 10)(i => s"wide-range $i" -> v.wideRange(rng)) ++
      Seq.tabulate(n / 20)(i => s"raw $i" -> v.rawLink(rng))
    (all.map(_._1).toIndexedSeq, all.map(_._2).toIndexedSeq)
  }

  /** Checks an fp32 RNE correctly rounded result against plain JVM float arithmetic too. */
  private def floatOracle(cfg: ScpuConfig, pairs: IndexedSeq[ScpuPair]): (Int, ScpuResult) => Unit =
    if (cfg != ScpuConfig.fp32) (_, _) => ()
    else (i, got) => {
      val o = FloatOde.collide(pairs(i))
      assert(FloatOde.agrees(got, o), s"fp32 RTL pair $i differs from JVM float: ${pairs(i)}\n  rtl  ${got.show}\n  jvm  $o")
    }

  private def runBank(cfgs: Seq[ScpuConfig], counts: ScpuConfig => Int, seedName: String): Unit = {
    val rng = Seeds.rng(seedName)
    val sets = cfgs.map { c =>
      val (labels, pairs) = vectors(c, counts(c), new Random(rng.nextLong()))
      val model = ScpuModel(c)
      (labels, pairs, pairs.map(model.collide))
    }
    val t0 = System.nanoTime()
    test(new ScpuBank(cfgs)).withAnnotations(annos) { dut =>
      val t1 = System.nanoTime()
      val ports = cfgs.indices.map(i => dut.io(i).asInstanceOf[ScpuPort])
      // Phase 1: the hard cases back to back with out.ready high: each result exactly
      // `latency` cycles after its pair, one pair per cycle.
      val burst = cfgs.indices.map { i =>
        val k = math.min(200, sets(i)._2.size)
        new ScpuLane(ports(i), cfgs(i).latency, sets(i)._2.take(k), sets(i)._3.take(k), new Random(1), 0, 0, sets(i)._1.take(k))
      }
      ScpuDriver.run(dut.clock, burst, 10000)
      for ((l, i) <- burst.zipWithIndex)
        assert(l.cycles == math.min(200, sets(i)._2.size) + cfgs(i).latency, s"${cfgs(i).name}: ${l.cycles} cycles for a burst")
      // Phase 2: everything, with 10% input bubbles and out.ready low 25% of the time.
      val lanes = cfgs.indices.map { i =>
        val (labels, pairs, exp) = sets(i)
        new ScpuLane(ports(i), cfgs(i).latency, pairs, exp, new Random(rng.nextLong()), 25, 10, labels, floatOracle(cfgs(i), pairs))
      }
      val cycles = ScpuDriver.run(dut.clock, lanes, 20 * sets.map(_._2.size).max + 1000)
      info(cfgs.zip(sets).map { case (c, s) => s"${c.name}: ${s._2.size} pairs (latency ${c.latency})" }.mkString("; ") +
        f"; $cycles cycles; build ${(t1 - t0) / 1e9}%.0f s, simulation ${(System.nanoTime() - t1) / 1e9}%.0f s")
    }
  }

  private val defaultCount = Seeds.cases(20000)

  it should "match its golden model bit for bit for every preset, streaming one pair per cycle under random stalls" in {
    // fp64 is the costly lane to build, not to run; 2,000 pairs here, 20,000 in the Slow test.
    runBank(ScpuConfig.all, c => if (c == ScpuConfig.fp64) defaultCount / 10 else defaultCount, "ScpuSpec-all")
  }

  it should "match its golden model bit for bit with every operator as deep as a 200 MHz clock needs (mhz=200), and placed for ECP5" in {
    // FpAdd and FpMul at the latencies their estimated stages need, every root stage registered,
    // the Robust method's scaling in four stages, the conversions in four, and ECP5's 18-bit tiles.
    val deep = Seq("fp32:mhz=200", "fp16-robust:mhz=200", "fp24:mhz=200", "bf16:family=ecp5:mhz=100", "fp32-rsqrt-dr:mhz=200")
      .map(s => ScpuConfig.parse(s).fold(e => fail(e), identity))
    runBank(deep, _ => Seeds.cases(4000), "ScpuSpec-deep")
  }

  it should "match its golden model on 20,000 pairs for fp64" taggedAs Slow in {
    runBank(Seq(ScpuConfig.fp64), _ => Seeds.cases(20000), "ScpuSpec-fp64")
  }

  it should "be named after its configuration and report the configuration's latency" in {
    val v = circt.stage.ChiselStage.emitSystemVerilog(new Scpu(ScpuConfig.fp16Robust))
    assert(v.contains("module Scpu_fp16_robust(") && v.contains("RobustDistance_fp16_robust"))
    val custom = ScpuConfig.fp16Robust.copy(addLatency = 2)
    assert(custom.id != ScpuConfig.fp16Robust.id && custom.latency > ScpuConfig.fp16Robust.latency)
  }
}
