package collide.afu

import chisel3._
import chiseltest._
import chiseltest.simulator.{VerilatorBackendAnnotation, VerilatorCFlags}
import collide.scpu.model.ScpuModel

/** Steady-state cycles per pair against the number of SCPUs, on an ideal memory (1-cycle
  * latency, a line a cycle each way, no back-pressure), compact records, few hits (so the
  * write channel never limits). Steady state = (C(P2) - C(P1)) / (P2 - P1) for two pair-list
  * sizes: load, pipeline fill and drain cancel out.
  *
  *   sbt "Test/runMain collide.afu.AfuCycleReport"            (prints the table)
  *   sbt "Test/runMain collide.afu.AfuCycleReport --write"    (also writes bench/afu-cycles.md)
  *   options: --scpus 1,2,4,8,16  --pairs 2048,10240  --preset default
  */
object AfuCycleReport {
  final case class Row(n: Int, peak: Double, c1: Long, c2: Long, p1: Int, p2: Int, st: Status, contacts: Long) {
    def cpp: Double = (c2 - c1).toDouble / (p2 - p1)
  }

  def measure(cfg: AfuConfig, p1: Int, p2: Int, seed: Long): Row = {
    var out: Option[Row] = None
    RawTester.test(new Afu(cfg), Seq(VerilatorBackendAnnotation, VerilatorCFlags(Seq("-O1")))) { dut =>
      dut.clock.setTimeout(0)
      val rnd = new scala.util.Random(seed)
      val lf = cfg.scpu.linkFormat
      val ns = cfg.maxSpheres
      // spheres spread thinly over a 60-unit box: about 1 pair in 2000 collides
      val spheres = (0 until ns).map(_ => Seq(rnd.nextDouble() * 60, rnd.nextDouble() * 60, rnd.nextDouble() * 60,
        0.1 + rnd.nextDouble() * 0.4).map(ScpuModel.fromDouble(lf, _)))
      val all = (0 until p2).map(_ => (rnd.nextInt(ns), rnd.nextInt(ns)))
      def runOnce(p: Int): RunResult = {
        val w = World(cfg.layout, spheres, all.take(p), dense = false)
        val r = AfuRun.run(new HostMemoryModel(dut.io, dut.clock, LinkBehaviour.ideal, seed, cfg.maxReadsOutstanding,
          cfg.maxWritesOutstanding), w, maxCycles = 50L * p + 100000)
        val errs = AfuRun.check(w, AfuWorlds.expect(cfg.scpu, w), r)
        require(errs.isEmpty, s"${cfg.id}: ${errs.mkString("; ")}")
        r
      }
      val r1 = runOnce(p1); val r2 = runOnce(p2)
      out = Some(Row(cfg.scpus, cfg.peakPairsPerCycle, r1.status.get.cycles, r2.status.get.cycles, p1, p2, r2.status.get,
        r2.status.get.found))
    }
    out.get
  }

  def machine: String = {
    import scala.sys.process._
    val nproc = scala.util.Try("nproc".!!.trim).getOrElse("?")
    val model = scala.util.Try(Seq("sh", "-c", "lscpu | grep 'Model name'").!!.trim.replaceAll("\\s+", " ")).getOrElse("?")
    s"nproc = $nproc; $model"
  }

  def main(args: Array[String]): Unit = {
    def arg(name: String): Option[String] = args.sliding(2).collectFirst { case Array(`name`, v) => v }
    val ns = arg("--scpus").map(_.split(",").map(_.toInt).toSeq).getOrElse(Seq(1, 2, 4, 8, 16))
    val Array(p1, p2) = arg("--pairs").getOrElse("2048,10240").split(",").map(_.toInt)
    val preset = arg("--preset").getOrElse("default")
    val base = AfuConfig.presets(preset)
    val t0 = System.nanoTime()
    val rows = ns.map(n => measure(base.copy(scpus = n), p1, p2, 1234L + n))
    val secs = (System.nanoTime() - t0) / 1e9
    val b = new StringBuilder
    b ++= s"# AFU cycles per pair against SCPUs (ideal memory)\n\n"
    b ++= s"Command: `sbt \"Test/runMain collide.afu.AfuCycleReport${if (args.nonEmpty) " " + args.mkString(" ") else ""}\"`  \n"
    b ++= s"Machine: $machine  \n"
    b ++= s"Configuration: preset `$preset` (${base.scpu.describe}), number of SCPUs varied; " +
      s"memory: 1-cycle read and write latency, one line a cycle each way, no back-pressure; compact records; " +
      s"${base.maxSpheres} spheres, random pairs (few hits).  \n"
    b ++= s"Steady state = (cycles($p2 pairs) - cycles($p1 pairs)) / ${p2 - p1}; total = start to status write for $p2 pairs. " +
      f"Took $secs%.0f s (Verilator builds included).\n\n"
    b ++= "| SCPUs | peak pairs/cycle | steady cycles/pair | steady pairs/cycle | total cycles | load cycles | compute cycles | contacts |\n"
    b ++= "|---:|---:|---:|---:|---:|---:|---:|---:|\n"
    for (r <- rows)
      b ++= f"| ${r.n} | ${r.peak}%.2f | ${r.cpp}%.4f | ${1 / r.cpp}%.2f | ${r.c2} | ${r.st.cycLoad} | ${r.st.cycCompute} | ${r.contacts} |\n"
    b ++= "\nA pair line holds 16 pairs and the link brings one line a cycle, so 16 pairs a cycle is the " +
      "ceiling; a dispatch group never spans two lines, so N that does not divide 16 reaches 16 / ceil(16 / N).\n"
    print(b.toString)
    if (args.contains("--write")) {
      java.nio.file.Files.createDirectories(java.nio.file.Paths.get("bench"))
      java.nio.file.Files.write(java.nio.file.Paths.get("bench/afu-cycles.md"), b.toString.getBytes("UTF-8"))
      println("wrote bench/afu-cycles.md")
    }
  }
}
