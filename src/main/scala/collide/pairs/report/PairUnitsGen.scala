package collide.pairs.report

import java.nio.file.{Files, Paths}
import collide.pairs.{CapsuleSphere, SpherePlane}
import collide.scpu.{ScpuConfig, ScpuDatapath}

/** Writes each pair kind's unit as SystemVerilog for the area and timing proxies
  * (bench/pairs/unit_cost.py): for each SCPU configuration, the sphere SCPU's datapath
  * (sphere/sphere), SpherePlane and CapsuleSphere, one file each, and prints
  * "<file> <top> <latency> <kind> <scpu>" a line.
  *
  * usage: tools/sbt "runMain collide.pairs.report.PairUnitsGen --out DIR SPEC..." (SPEC as
  * ScpuConfig.parse takes it, e.g. fp32:mhz=200)
  */
object PairUnitsGen {
  def main(args: Array[String]): Unit = {
    val out = args.sliding(2).collectFirst { case Array("--out", d) => d }.getOrElse("build/pair-units")
    val given = args.toSeq.filterNot(a => a == "--out" || a == out)
    val cfgs = (if (given.isEmpty) Seq("fp16:mhz=200", "fp32:mhz=200") else given).map { s =>
      ScpuConfig.parse(s).fold(e => { System.err.println(s"PairUnitsGen: $s: $e"); sys.exit(2) }, c => s -> c)
    }
    Files.createDirectories(Paths.get(out))
    for ((spec, cfg) <- cfgs) {
      val units: Seq[(String, () => chisel3.RawModule, String, Int)] = Seq(
        ("sphere-sphere", () => new ScpuDatapath(cfg), s"ScpuDatapath_${cfg.id}", cfg.coreLatency),
        ("sphere-plane", () => new SpherePlane(cfg), s"SpherePlane_${cfg.id}", SpherePlane.latency(cfg)),
        ("capsule-sphere", () => new CapsuleSphere(cfg), s"CapsuleSphere_${cfg.id}", CapsuleSphere.latency(cfg)))
      for ((kind, gen, top, lat) <- units) {
        val sv = _root_.circt.stage.ChiselStage.emitSystemVerilog(gen(), firtoolOpts = collide.Generate.firtoolOpts)
        val file = Paths.get(out, s"$top.sv")
        Files.writeString(file, sv)
        println(s"$file $top $lat $kind $spec")
      }
    }
  }
}
