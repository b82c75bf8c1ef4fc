package collide.afu

import chisel3._
import chiseltest._
import chiseltest.simulator.{VerilatorBackendAnnotation, WriteVcdAnnotation}
import org.scalatest.flatspec.AnyFlatSpec
import collide.testutil.{Seeds, Slow}

/** The whole AFU (PUC + real SCPUs) against ScpuModel, end to end over the modelled link:
  * random seeded worlds (hits, misses, coincident and grazing pairs, NaN and infinities,
  * bad indices), compact and dense, on hostile and HARP-like links. Each model is built
  * once (Verilator) and runs many worlds. -Dvcd=1 writes a waveform. */
class AfuSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "Afu"

  val annos = Seq(VerilatorBackendAnnotation) ++
    (if (sys.props.contains("vcd")) Seq(WriteVcdAnnotation) else Nil)

  def endToEnd(cfg: AfuConfig, worlds: Int, maxPairs: Int = 120,
               behaviours: Seq[LinkBehaviour] = Seq(LinkBehaviour.hostile, LinkBehaviour.harp, LinkBehaviour.ideal),
               minPairs: Int = 0): Long = {
    val rnd = Seeds.rng(s"AfuSpec-${cfg.id}")
    var pairsRun = 0L; var hits = 0L
    test(new Afu(cfg)).withAnnotations(annos) { dut =>
      dut.clock.setTimeout(0)
      for (i <- 0 until worlds) {
        val b = behaviours(i % behaviours.size)
        val world = AfuWorlds.random(rnd, cfg, minPairs + rnd.nextInt(maxPairs - minPairs + 1),
          dense = i % 2 == 1, specials = i % 3 == 2)
        val capped = if (i % 5 == 4) world.copy(capacity = Some(rnd.nextInt(world.pairs.size / 4 + 2).toLong)) else world
        val mem = new HostMemoryModel(dut.io, dut.clock, b, rnd.nextLong(), cfg.maxReadsOutstanding, cfg.maxWritesOutstanding)
        val r = AfuRun.run(mem, capped)
        val errs = AfuRun.check(capped, AfuWorlds.expect(cfg.scpu, capped), r)
        assert(errs.isEmpty, s"${cfg.id} world $i (${b.name}, ${capped.pairs.size} pairs, dense=${capped.dense}, " +
          s"cap=${capped.capacity}): ${errs.mkString("; ")}\n${r.status}")
        pairsRun += capped.pairs.size; hits += r.status.get.found
      }
      println(s"[AfuSpec] ${cfg.id} (${cfg.scpu.linkFormat.name} link, ${cfg.recordLayout.name} records): $worlds worlds, $pairsRun pairs, $hits contacts, all equal to ScpuModel")
    }
    pairsRun
  }

  it should "equal ScpuModel with one fp32 SCPU (derived records)" in {
    endToEnd(AfuConfig.default.copy(scpus = 1, maxSpheres = 512, records = Some(RecordLayout.Derived)), Seeds.cases(12))
  }
  it should "equal ScpuModel with one fp32 SCPU (full records)" in {
    endToEnd(AfuConfig.paper.copy(scpus = 1, maxSpheres = 512), Seeds.cases(8))
  }
  it should "equal ScpuModel with two fp16 SCPUs on a binary16 link (derived-masked records: a header fills its slot)" in {
    endToEnd(AfuConfig.fp16.copy(scpus = 2, maxSpheres = 512), Seeds.cases(12))
  }
  it should "equal ScpuModel with two bf16 SCPUs on a bfloat16 link (full records)" in {
    endToEnd(AfuConfig.fp16Full.copy(scpus = 2, maxSpheres = 512, scpu = collide.scpu.ScpuConfig.bf16), Seeds.cases(8))
  }
  it should "equal ScpuModel with four fp32 SCPUs (derived-masked records)" in {
    endToEnd(AfuConfig.default.copy(scpus = 4, maxSpheres = 512, records = Some(RecordLayout.DerivedMasked)), Seeds.cases(9))
  }
  it should "equal ScpuModel in the default preset (16 fp32 SCPUs)" taggedAs Slow in {
    endToEnd(AfuConfig.default, Seeds.cases(9), maxPairs = 400)
  }
  it should "equal ScpuModel with sixteen fp16 SCPUs" taggedAs Slow in {
    endToEnd(AfuConfig.fp16, Seeds.cases(6), maxPairs = 400)
  }
  it should "equal ScpuModel with two fp64 SCPUs (binary64 link)" taggedAs Slow in {
    endToEnd(AfuConfig.fp64.copy(scpus = 2, maxSpheres = 256), Seeds.cases(6))
  }
  it should "account for every one of 100,000 pairs exactly once over a hostile link (soak)" taggedAs Slow in {
    // Reordered, back-pressured, latencies of 1..60 cycles; compact and dense, capacities cut
    // short, NaNs and bad indices: AfuRun.check accounts for every pair of every world.
    val n = endToEnd(AfuConfig.default.copy(scpus = 4, maxSpheres = 512), Seeds.cases(25), maxPairs = 4400,
      behaviours = Seq(LinkBehaviour.hostile), minPairs = 4000)
    assert(n >= 100000L * Seeds.cases(25) / 25, s"only $n pairs")
  }
}
