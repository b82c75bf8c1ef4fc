package collide.world

import java.nio.file.{Files, Paths}
import scala.jdk.CollectionConverters._
import chisel3._
import chiseltest._
import chiseltest.simulator.{VerilatorBackendAnnotation, VerilatorCFlags}
import collide.fp.FloatFormat
import collide.scpu.ScpuConfig
import collide.world.BroadPhaseWorlds._
import collide.world.model._

/** Cycles of the broad phase's RTL on Verilator, pass by pass, for uniform and clustered
  * clouds of growing size (and uniform ones with four huge spheres, for the large pass),
  * beside the golden model's work counts and its cycle estimate, for each number of
  * candidate-generator lanes and sort ports asked for (default one of each; a port count above
  * the lanes is skipped). bench/world/fit_cycles.py fits the linear model to the one-lane
  * rows; bench/world/lanes.py reports the lanes and ports.
  *
  *   sbt "Test/runMain collide.world.BroadPhaseCycleReport [--sizes 500,1000,...] [--max 16384]
  *        [--spheres FILE.csv ...] [--lanes 1,4,16] [--sort-ports 1,2,4] [--word-log2 3]
  *        [--buckets-per-sphere-log2 1] [--cell-steps 2] [--chunk 32] [--coarse-chunks true] [--team 4] [--claims true] [--hit-queue 4] [--box-buckets true] [--out FILE.csv]"
  *
  * --word-log2 sets BroadPhaseParams.wordLog2 (counters a RAM word: clear, prefix and the walk
  * take a word a cycle) and --buckets-per-sphere-log2 BroadPhaseParams.bucketsPerSphereLog2
  * for every configuration of the run (the buckets column says what each world used), and
  * --cell-steps BroadPhaseParams.cellSteps (1: cell edges 2^k alone; 2: also 1.5 * 2^k),
  * --chunk BroadPhaseParams.chunk (spheres a generator holds) and --coarse-chunks
  * BroadPhaseParams.coarseChunks (a coarse cell of 2 x 2 x 2 cells one chunk where it fits),
  * --box-buckets BroadPhaseParams.boxBuckets (the box_extents column: each world's box in units
  * along x, y and z, the RTL's checked against the model's, or "hash"; CSVs from before the
  * padded box map have box_bits, its bits per axis, instead).
  *
  * --spheres adds a world from a `collide spheres` input file (one a flag, repeat it; header x,y,z,r; decimal or hex
  * floats, binary32 values), e.g. bench/world/world.py --dump-clouds DIR: the very spheres
  * the CPU backends were timed on. Its row is named after the file.
  *
  * The pair stream is always ready (the SCPUs' side is measured by the AFU's own reports),
  * and every world's pairs are checked against the model's as the spec does.
  */
object BroadPhaseCycleReport {
  def readSpheres(file: String): (String, Seq[S]) = {
    val path = Paths.get(file)
    require(Files.isRegularFile(path), s"--spheres $file: no such file")
    val lines = Files.readAllLines(path).asScala.toSeq
    require(lines.headOption.map(_.trim).contains("x,y,z,r"), s"$file: the header must be x,y,z,r")
    val spheres = lines.tail.zipWithIndex.filter(_._1.trim.nonEmpty).map { case (l, i) =>
      val f = l.split(',').map(_.trim)
      require(f.length == 4, s"$file line ${i + 2}: expected 4 fields, got ${f.length}")
      def num(v: String) = try java.lang.Double.parseDouble(v) catch {
        case _: NumberFormatException => throw new IllegalArgumentException(s"$file line ${i + 2}: '$v' is not a number")
      }
      S(num(f(0)), num(f(1)), num(f(2)), num(f(3)))
    }
    (path.getFileName.toString.stripSuffix(".csv"), spheres)
  }

  def main(args: Array[String]): Unit = {
    var sizes = Seq(500, 1000, 2000, 4000, 8000, 16000); var maxSpheres = 16384; var out: Option[String] = None
    var files = Seq.empty[String]
    var lanes = Seq(1)
    var ports = Seq(1)
    var wordLog2 = BroadPhaseParams.default.wordLog2
    var bpsLog2 = BroadPhaseParams.default.bucketsPerSphereLog2
    var cellSteps = BroadPhaseParams.default.cellSteps
    var chunk = BroadPhaseParams.default.chunk
    var coarse = false
    var team = BroadPhaseParams.default.team
    var claims = BroadPhaseParams.default.claims
    var feed = 0
    var hitQueue = BroadPhaseParams.default.hitQueue
    var boxBuckets = BroadPhaseParams.default.boxBuckets
    var drainBehind = BroadPhaseParams.default.drainBehind
    var lookAhead = BroadPhaseParams.default.lookAhead
    var scanPairs = BroadPhaseParams.default.scanPairs
    var clearBehind = BroadPhaseParams.default.clearBehind
    args.sliding(2, 2).foreach {
      case Array("--sizes", v) => sizes = v.split(',').map(_.trim.toInt).toSeq
      case Array("--max", v)   => maxSpheres = v.toInt
      case Array("--out", v)   => out = Some(v)
      case Array("--spheres", v) => files :+= v
      case Array("--lanes", v) => lanes = v.split(',').map(_.trim.toInt).toSeq
      case Array("--sort-ports", v) => ports = v.split(',').map(_.trim.toInt).toSeq
      case Array("--word-log2", v) => wordLog2 = v.trim.toInt
      case Array("--buckets-per-sphere-log2", v) => bpsLog2 = v.trim.toInt
      case Array("--cell-steps", v) => cellSteps = v.trim.toInt
      case Array("--chunk", v) => chunk = v.trim.toInt
      case Array("--coarse-chunks", v) => coarse = v.trim.toBoolean
      case Array("--team", v) => team = v.trim.toInt
      case Array("--claims", v) => claims = v.trim.toBoolean
      case Array("--feed", v) => feed = v.trim.toInt
      case Array("--hit-queue", v) => hitQueue = v.trim.toInt
      case Array("--box-buckets", v) => boxBuckets = v.trim.toBoolean
      case Array("--drain-behind", v) => drainBehind = v.trim.toBoolean
      case Array("--clear-behind", v) => clearBehind = v.trim.toBoolean
      case Array("--look-ahead", v) => lookAhead = v.trim.toInt
      case Array("--scan-pairs", v) => scanPairs = v.trim.toBoolean
      case a => throw new IllegalArgumentException(s"unknown option ${a.mkString(" ")} (expected --sizes, --max, --spheres, --lanes, --sort-ports, --word-log2, --buckets-per-sphere-log2, --cell-steps, --chunk, --coarse-chunks, --team, --claims, --hit-queue, --box-buckets, --drain-behind, --look-ahead, --scan-pairs, --clear-behind, --feed, --out)")
    }
    require(feed >= 0 && lanes.forall(feed <= _), s"--feed (spheres fed a cycle as the table arrives, the AFU's spheres a line) must be 0..the lanes, got $feed")
    require(sizes.forall(n => n >= 1 && n <= maxSpheres), s"--sizes must be 1..--max ($maxSpheres)")
    require(lanes.nonEmpty && lanes.forall(l => l >= 1 && l <= 32), s"--lanes must be 1..32, got ${lanes.mkString(",")}")
    require(ports.nonEmpty && ports.forall(BroadPhaseParams.sortPortChoices.contains), s"--sort-ports must be among ${BroadPhaseParams.sortPortChoices.mkString(",")}, got ${ports.mkString(",")}")
    val cfg = ScpuConfig.fp32
    val rng = new scala.util.Random(1)
    // "huge": the uniform cloud plus four spheres of radius 20 to 1280, the large pass's work.
    val worlds = sizes.flatMap(n => Seq(s"uniform" -> uniform(rng, n), s"clustered" -> clustered(rng, n, clusters = 1 + n / 200),
      s"huge" -> huge(rng, n - 4, 4))) ++ files.map(readSpheres)
    require(worlds.forall(_._2.length <= maxSpheres), s"a world has more than --max ($maxSpheres) spheres")
    val header = "world,spheres,buckets,cells,chunks,scanned,probes,candidates,large," +
      "load,classify,prefix,scatter,grid,large_pass,total,model_generate,model_total,lanes,sort_ports,word_log2,cell_steps,chunk,coarse_chunks,team,feed,claims,hit_queue,box_buckets,box_extents,drain_behind,look_ahead,scan_pairs," +
      GridCycle.names.map(n => "lane_" + n.replaceAll("([A-Z])", "_$1").toLowerCase).mkString(",")
    val rows = scala.collection.mutable.ArrayBuffer(header)
    for (l <- lanes; q <- ports if q <= l) {
      val model = new BroadPhaseModel(cfg, BroadPhaseParams.default.copy(lanes = l, sortPorts = q, wordLog2 = wordLog2,
        bucketsPerSphereLog2 = bpsLog2, cellSteps = cellSteps, chunk = chunk, coarseChunks = coarse, team = team, claims = claims, hitQueue = hitQueue, boxBuckets = boxBuckets, drainBehind = drainBehind, lookAhead = lookAhead, scanPairs = scanPairs, clearBehind = clearBehind))
      RawTester.test(new BroadPhase(cfg.params, model.bp, maxSpheres, feedWidth = feed), Seq(VerilatorBackendAnnotation, VerilatorCFlags(Seq("-O1")))) { dut =>
        dut.clock.setTimeout(0)
        for ((name, ws) <- worlds) {
          val world = bits(FloatFormat.fp32, ws)
          val want = model.run(world)
          val table = world.map(model.converted)
          val (pairs, _, _) = BroadPhaseDriver.run(dut, table, () => true, Long.MaxValue, if (feed > 0) Some(new BroadPhaseDriver.Feeder(dut, table, rng)) else None) { _ =>
            throw new IllegalStateException(s"$name ${ws.length}: the broad phase never finished")
          }
          require(pairs.sorted == want.candidates.sorted, s"$name ${ws.length}: the RTL's pairs differ from the model's")
          val s = dut.io.status
          def v(d: UInt) = d.peek().litValue
          val c = model.cycles(want, lanes = l, scpus = 16, sortRate = q)
          val box = want.stats.box.map(_.reported(BoxMapBits.extentW))
          require(s.laneCycles.map(v).sum == l * v(s.cycGrid), s"$name ${ws.length}: the lane-cycles do not add up to lanes x grid cycles")
          require(box.forall(_ == s.box.map(v(_).toLong)), s"$name ${ws.length}: the RTL's box extents ${s.box.map(v(_))} are not the model's $box")
          val row = (Seq(name, ws.length, want.stats.buckets, v(s.cells), v(s.chunks), v(s.scanned), v(s.probes), v(s.candidates),
            v(s.large), v(s.cycLoad), v(s.cycClassify), v(s.cycPrefix), v(s.cycScatter), v(s.cycGrid), v(s.cycLarge), v(s.cycTotal),
            c.generate, c.count + c.prefix + c.scatter + c.generate + c.large, l, q, wordLog2, cellSteps, chunk, coarse, team, feed, claims, hitQueue, boxBuckets,
            box.map(_.mkString("x")).getOrElse("hash"), drainBehind, lookAhead, scanPairs) ++ s.laneCycles.map(v)).mkString(",")
          println(row)
          rows += row
        }
      }
    }
    out.foreach { f => Files.createDirectories(Paths.get(f).toAbsolutePath.getParent); Files.write(Paths.get(f), (rows.mkString("\n") + "\n").getBytes) }
  }
}
