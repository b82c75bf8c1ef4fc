package collide.world

import java.nio.file.{Files, Paths}
import scala.jdk.CollectionConverters._
import collide.fp.FloatFormat
import collide.scpu.ScpuConfig
import collide.world.BroadPhaseWorlds._
import collide.world.model._

/** The broad-phase model's work and its cycle model on large worlds, against the link bound
  * of world mode (sphere table in, contacts out). A sizing study for the hardware: every
  * count comes from the model's traversal; the cycles are BroadPhaseCycles' model.
  *
  *   sbt "Test/runMain collide.world.BroadPhaseReport [--csv FILE:RADIUS ...] [--sizes 670,10000,65536] [--cell-steps 1|2] [--chunk 16] [--coarse-chunks true] [--out FILE]"
  *
  * --csv reads `collide run --positions` output (header sphere,x,y,z; all spheres of radius
  * RADIUS), e.g. the diamond at a larger hMax. Contacts are counted exactly in binary64 on
  * the candidates (the specs prove candidates hold every hit).
  */
object BroadPhaseReport {
  // Link figures (docs/host.md, link presets): HARP v1 reads 7 GB/s, writes 5 GB/s, 5 us
  // fixed per call; the ideal link moves a 64-byte line a cycle each way at 200 MHz.
  final case class Link(name: String, readGBps: Double, writeGBps: Double, fixedNs: Double)
  val links = Seq(Link("harp1", 7.0, 5.0, 5000.0 + 125 + 290), Link("ideal", 12.8, 12.8, 0.0))
  val sphereBytes = 16  // x, y, z, r in binary32
  val recordBytes = 32  // assumed world-mode record: i, j (16 bits each) and 7 binary32 fields
  val clockMHz = 200.0

  def readCsv(spec: String): (String, Seq[S]) = {
    val (file, radius) = spec.lastIndexOf(':') match {
      case -1 => throw new IllegalArgumentException(s"--csv $spec: expected FILE:RADIUS")
      case i  => (spec.take(i), spec.drop(i + 1).toDouble)
    }
    val lines = Files.readAllLines(Paths.get(file)).asScala.toSeq
    require(lines.headOption.contains("sphere,x,y,z"), s"$file: header must be sphere,x,y,z")
    val spheres = lines.tail.filter(_.nonEmpty).map { l =>
      val f = l.split(',').map(_.trim)
      S(java.lang.Double.parseDouble(f(1)), java.lang.Double.parseDouble(f(2)), java.lang.Double.parseDouble(f(3)), radius)
    }
    (Paths.get(file).getFileName.toString.stripSuffix(".csv"), spheres)
  }

  def main(args: Array[String]): Unit = {
    var csvs = Seq.empty[String]; var sizes = Seq(670, 10000, 65536); var out: Option[String] = None
    var cellSteps = BroadPhaseParams.default.cellSteps
    var chunk = BroadPhaseParams.default.chunk
    var coarseChunks = false
    args.sliding(2, 2).foreach {
      case Array("--csv", v)   => csvs :+= v
      case Array("--sizes", v) => sizes = v.split(',').map(_.toInt).toSeq
      case Array("--out", v)   => out = Some(v)
      case Array("--cell-steps", v) => cellSteps = v.toInt
      case Array("--chunk", v) => chunk = v.toInt
      case Array("--coarse-chunks", v) => coarseChunks = v.toBoolean
      case a => throw new IllegalArgumentException(s"unknown option ${a.mkString(" ")}")
    }
    val rng = new scala.util.Random(1)
    val worlds = sizes.flatMap(n => Seq(s"uniform $n" -> uniform(rng, n), s"clustered $n" -> clustered(rng, n, clusters = 1 + n / 200))) ++
      csvs.map(readCsv)
    val model = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.default.copy(bucketsLog2 = 18, cellSteps = cellSteps,
      chunk = chunk, coarseChunks = coarseChunks))
    val sb = new StringBuilder
    sb ++= "| world | spheres | cell edge | large | cells | candidates/sphere | scanned/sphere | contacts | lanes | sort/cycle | count+prefix+scatter | generate | narrow | model cycles | model us | harp1 est./bound us | ideal est./bound us |\n"
    sb ++= "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
    for ((name, ws) <- worlds) {
      val w = ws.toIndexedSeq
      val r = model.run(bits(FloatFormat.fp32, w))
      val contacts = r.candidates.count { case (i, j) =>
        val a = w(i); val b = w(j)
        val d2 = (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z)
        d2 <= (a.r + b.r) * (a.r + b.r)
      }
      val n = w.length
      def readUs(l: Link) = n * sphereBytes / l.readGBps / 1000
      def writeUs(l: Link) = contacts.toLong * recordBytes / l.writeGBps / 1000
      def bound(l: Link) = l.fixedNs / 1000 + readUs(l) + writeUs(l)
      // The table must be in before k is known; contacts stream out while candidates are made.
      def estimate(l: Link, computeUs: Double) = l.fixedNs / 1000 + readUs(l) + math.max(computeUs, writeUs(l))
      def cell(l: Link, computeUs: Double) = f"${estimate(l, computeUs)}%.0f / ${bound(l)}%.0f (${estimate(l, computeUs) / bound(l)}%.2fx)"
      for ((lanes, sortRate) <- Seq((1, 1), (16, 1), (16, 4))) {
        val c = model.cycles(r, lanes = lanes, scpus = 16, sortRate = sortRate)
        sb ++= f"| $name | $n | ${BroadPhaseParams.edge(r.level)}%g | ${r.stats.large} | ${r.stats.cells} | ${r.stats.candidates.toDouble / n}%.2f | " +
          f"${r.stats.scanned.toDouble / n}%.1f | $contacts | $lanes | $sortRate | ${c.count + c.prefix + c.scatter} | " +
          f"${c.generate + c.large} | ${c.narrow} | ${c.total} | ${c.total / clockMHz}%.1f | ${cell(links(0), c.total / clockMHz)} | ${cell(links(1), c.total / clockMHz)} |\n"
      }
    }
    print(sb)
    out.foreach(f => Files.write(Paths.get(f), sb.toString.getBytes))
  }
}
