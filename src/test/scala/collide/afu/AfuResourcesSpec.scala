package collide.afu

import java.nio.file.Files
import org.scalatest.flatspec.AnyFlatSpec
import collide.Generate
import collide.scpu.{Scpu, ScpuConfig}

/** The device an AFU must fit: what the generator counts (M20K blocks by estimate, the FP
  * multipliers' DSP tiles at elaboration), what it refuses and what the manifest says. */
class AfuResourcesSpec extends AnyFlatSpec {
  behavior of "AfuResources"

  private def cfg(args: String*) =
    scopt.OParser.parse(Generate.parser, args, Generate.Opts()).map(Generate.config).getOrElse(fail(s"parse: $args"))
  private def tiles(c: ScpuConfig) = AfuResources.counting(circt.stage.ChiselStage.emitCHIRRTL(new Scpu(c)))._2

  it should "count every FP multiplier's DSP tiles as an SCPU is elaborated" in {
    // Ten FpMuls an SCPU (the squares, the normal and its scale); a 24- or 11-bit significand is
    // one 27 x 27 tile, a 53-bit one two by two.
    assert(tiles(ScpuConfig.fp32) == 10 && tiles(ScpuConfig.fp16) == 10 && tiles(ScpuConfig.fp64) == 40)
    assert(tiles(ScpuConfig.fp32At200) == 10, "depth adds registers, not tiles")
    // Nothing is counted outside an elaboration that asks.
    AfuResources.dspTiles(5)
    assert(AfuResources.counting(())._2 == 0)
  }

  it should "name each resource a configuration exceeds on its device, with both numbers" in {
    val d = Device.stratixVA7
    assert(AfuResources(416, Some(160)).overfit(d).isEmpty)
    val over = AfuResources(3000, Some(640)).overfit(d)
    assert(over == Seq("M20K blocks: 3000 needed (by estimate), the 5SGXEA7 has 2560",
      "DSP blocks: 640 needed (one per multiplier tile), the 5SGXEA7 has 256"), over)
    assert(AfuResources(100, None).overfit(d).isEmpty, "a DSP count not made is not a refusal")
  }

  it should "give every preset a device: the paper's part, a Stratix 10 GX 2800 for world mode, an Arria 10 for its study" in {
    assert(AfuConfig.default.device == Device.stratixVA7 && AfuConfig.cosim.device == Device.stratixVA7)
    assert(AfuConfig.world.device == Device.stratix10GX2800 && AfuConfig.world32.device == Device.arria10GX1150)
    assert(Device.stratix10GX2800.alms == 933120 && Device.stratix10GX2800.source.contains("S10-OVERVIEW"))
    assert(cfg("--device", "10ax115").toOption.get.device == Device.arria10GX1150)
    assert(cfg("--device", "xc7a35t").left.toOption.get.contains("--device: unknown device 'xc7a35t' (known: 5SGXEA7, 10AX115, 1SG280)"))
    // The default AFU's sphere table: 16 copies of 64 lines of 512 bits, 26 M20Ks each (1K x 20).
    assert(AfuResources.of(AfuConfig.default, Some(160)) == AfuResources(16 * 26, Some(160)))
    assert(AfuResources.of(AfuConfig.cosim, Some(0)).dspTiles.isEmpty, "the C++ model's SCPUs take no tiles to count")
  }

  it should "fit the world-fit preset to the paper's part, where the world preset is refused" in {
    val wf = AfuConfig.worldFit
    assert(wf.device == Device.stratixVA7 && wf.broadPhase.get.lanes == 8 && wf.scpus == 4)
    // Its tables (4 SCPU copies and the 8 lanes' 4, twice for the run queue) and sort RAMs.
    val r = AfuResources.of(wf, Some(40))
    assert(r.m20k == 772 && r.overfit(Device.stratixVA7).isEmpty, r)
    // The world preset on the same part: its M20K estimate alone is within it; what it does not
    // fit is logic, which the area proxy measures (timing.json), not the generator.
    assert(AfuResources.of(AfuConfig.world, Some(160)).m20k == 1924)
  }

  it should "refuse to generate a configuration beyond its device unless it is a study" in {
    val dir = new java.io.File(Files.createTempDirectory("collide-fit").toFile, "world32")
    // world32's tables and sort RAM: 4,096 M20Ks by estimate against the Arria 10's 2,713 (refused
    // before anything is elaborated).
    val e = intercept[IllegalArgumentException](Generate.generate(AfuConfig.world32, dir, split = false, verilog = false, command = "t"))
    assert(e.getMessage.contains("does not fit its device, 10AX115") && e.getMessage.contains("M20K blocks: 4096 needed") &&
      e.getMessage.contains("--allow-overfit"), e.getMessage)
    assert(!dir.exists, "nothing written, not even its folder")
    Generate.generate(AfuConfig.world32, dir, split = false, verilog = false, command = "t", allowOverfit = true)
    val m = ujson.read(Files.readAllBytes(new java.io.File(dir, "manifest.json").toPath))("device")
    assert(m("name").str == "10AX115" && !m("fits").bool && m("overfit").arr.head.str.startsWith("M20K blocks: 4096"))
    assert(m("utilization")("m20k")("used").num == 4096 && m("utilization")("m20k")("of").num == 2713)
  }

  it should "write the device and what the AFU takes of it into the manifest" in {
    val m = AfuManifest.json(AfuConfig.default, "", AfuResources.of(AfuConfig.default, Some(160)))("device")
    assert(m("name").str == "5SGXEA7" && m("alms").num == 234720 && m("m20k").num == 2560 && m("dspBlocks").num == 256)
    assert(m("fits").bool && m("utilization")("dsp")("used").num == 160 && m("utilization")("dsp")("share").num == 0.625)
    assert(m("utilization")("alms").isNull && m("source").str.contains("SV51001"))
  }
}
