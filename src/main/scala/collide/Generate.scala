package collide

import java.io.File
import java.nio.file.{Files, Paths, StandardCopyOption}
import collide.afu._
import collide.scpu.{ScpuConfig, ScpuImpl, ScpuModelUnit}
import collide.world.BroadPhaseParams

/** The generator CLI: `sbt "run --preset default"`, `sbt "run --scpus 4 --format fp16"`,
  * `sbt "run --help"`. Writes generated/<preset-or-derived-name>/ with the SystemVerilog and
  * manifest.json from one AfuConfig, and the configuration-independent contract headers
  * (AfuContract) beside the folder. */
object Generate {
  final case class Opts(
      preset: String = "default",
      scpus: Option[Int] = None,
      format: Option[String] = None,
      scpu: Option[String] = None,
      maxSpheres: Option[Int] = None,
      maxReads: Option[Int] = None,
      maxWrites: Option[Int] = None,
      tagBits: Option[Int] = None,
      ramPorts: Option[String] = None,
      dense: Option[Boolean] = None,
      records: Option[String] = None,
      out: String = "generated",
      folder: Option[String] = None,
      split: Boolean = false,
      noVerilog: Boolean = false,
      device: Option[String] = None,
      allowOverfit: Boolean = false,
      world: Option[Boolean] = None,
      worldLanes: Option[Int] = None,
      worldSortPorts: Option[Int] = None,
      worldBucketsPerSphere: Option[Int] = None,
      worldCellSteps: Option[Int] = None,
      worldChunk: Option[Int] = None,
      worldCoarseChunks: Option[Boolean] = None,
      worldClaims: Option[Boolean] = None,
      worldHitQueue: Option[Int] = None,
      worldDrainBehind: Option[Boolean] = None,
      worldLookAhead: Option[Int] = None,
      worldScanPairs: Option[Boolean] = None,
      worldBoxBuckets: Option[Boolean] = None,
      worldWordLog2: Option[Int] = None,
      scpuImpl: Option[String] = None,
      runQueue: Option[Boolean] = None,
      worldLineQueue: Option[Int] = None,
      worldClearBehind: Option[Boolean] = None,
      worldNearFilter: Option[Boolean] = None,
      startAhead: Option[Boolean] = None,
      listPresets: Boolean = false)

  private val builder = scopt.OParser.builder[Opts]
  val parser: scopt.OParser[Unit, Opts] = {
    import builder._
    scopt.OParser.sequence(
      programName("collide.Generate"),
      head("collide.Generate", "writes generated/<name>/ (SystemVerilog, manifest.json) and generated/afu_contract.{hpp,svh}"),
      opt[String]("preset").valueName("NAME").action((v, o) => o.copy(preset = v))
        .text(s"start from a preset (${AfuConfig.all.map(_.name).mkString(", ")}); default: default"),
      opt[Int]("scpus").valueName("N").action((v, o) => o.copy(scpus = Some(v))).text("SCPUs, 1..64"),
      opt[String]("format").valueName("F").action((v, o) => o.copy(format = Some(v)))
        .text("compute format: an SCPU preset (fp32, fp16, fp64, fp24, bf16) or eEmM / 'E,M'"),
      opt[String]("scpu").valueName("SPEC").action((v, o) => o.copy(scpu = Some(v)))
        .text("full SCPU configuration: preset[:key=value]* (e.g. fp32:rm=rtz:sqrt=nr8x2); see ScpuConfig.parse"),
      opt[Int]("max-spheres").valueName("N").action((v, o) => o.copy(maxSpheres = Some(v)))
        .text("on-chip sphere table entries (power of two, 64..65536)"),
      opt[Int]("max-reads").valueName("N").action((v, o) => o.copy(maxReads = Some(v))).text("reads in flight at most"),
      opt[Int]("max-writes").valueName("N").action((v, o) => o.copy(maxWrites = Some(v))).text("writes in flight at most"),
      opt[Int]("tag-bits").valueName("N").action((v, o) => o.copy(tagBits = Some(v))).text("link tag width"),
      opt[String]("ram-ports").valueName("S").action((v, o) => o.copy(ramPorts = Some(v)))
        .text("sphere table read ports: replicated (a copy per SCPU) | banked (one copy, 2 x min(N, 16) banks) | banked:B (B banks)"),
      opt[String]("records").valueName("L").action((v, o) => o.copy(records = Some(v)))
        .text(s"contact record layout: ${RecordLayout.all.map(_.name).mkString(" | ")} (default: derived where the host can rebuild it exactly, else full)"),
      opt[Boolean]("dense-default").valueName("true|false").action((v, o) => o.copy(dense = Some(v)))
        .text("MODE's reset value selects dense records"),
      opt[Boolean]("world").valueName("true|false").action((v, o) => o.copy(world = Some(v)))
        .text("build world mode (MODE bit 1: the on-chip broad phase, default parameters; at most 4096 spheres)"),
      opt[Int]("world-lanes").valueName("L").action((v, o) => o.copy(worldLanes = Some(v)))
        .text("the broad phase's candidate generators, 1..32 (world mode only; past 16 they share the pair lines, 16 candidates a cycle; each adds a copy of its sort RAM, " +
          "and every two a copy of the sphere table; the sort's ports follow down to L)"),
      opt[Int]("world-sort-ports").valueName("P").action((v, o) => o.copy(worldSortPorts = Some(v)))
        .text("spheres a cycle in the broad phase's sort passes, 1, 2, 4, 8 or 16, at most the lanes (world mode only; " +
          "2 adds a table of counters, 4 is two sorts of half the table: a second table of counters a lane, 8 four sorts of a quarter, 16 eight of an eighth)"),
      opt[Int]("world-buckets-per-sphere").valueName("B").action((v, o) => o.copy(worldBucketsPerSphere = Some(v)))
        .text("buckets a world uses per sphere, 1, 2 (default) or 4 (world mode only; 1 halves the sort's counters " +
          "and its clear and prefix sum, for more cells sharing a bucket)"),
      opt[Int]("world-cell-steps").valueName("S").action((v, o) => o.copy(worldCellSteps = Some(v)))
        .text("cell edges an octave in the broad phase's grid, 1 (default: powers of two) or 2 (also 1.5 * 2^k: " +
          "cells nearer the spheres' size, faster on dense clusters, slower on sparse clouds; world mode only)"),
      opt[Int]("world-chunk").valueName("C").action((v, o) => o.copy(worldChunk = Some(v)))
        .text("spheres a candidate generator holds at once, its comparators, 1..256 (world mode only; default 16)"),
      opt[Boolean]("world-coarse-chunks").valueName("true|false").action((v, o) => o.copy(worldCoarseChunks = Some(v)))
        .text("a coarse cell (2 x 2 x 2 cells) whose spheres fit a chunk is one chunk, streaming 43 cells past it " +
          "instead of 14 a cell (world mode only; needs 8 or more counters a word)"),
      opt[Boolean]("world-claims").valueName("true|false").action((v, o) => o.copy(worldClaims = Some(v)))
        .text("the candidate lanes claim units of buckets from a shared counter as they need them, and the units that " +
          "are not one coarse chunk a bucket at a time, instead of walking fixed shares (world mode only)"),
      opt[Int]("world-word-log2").valueName("W").action((v, o) => o.copy(worldWordLog2 = Some(v)))
        .text("2^W counters a RAM word in the broad phase's sort, 0..5: the clear, the prefix sum and the walk take a " +
          "word a cycle (world mode only; coarse chunks need 3 or more; the preset has 5)"),
      opt[Int]("world-hit-queue").valueName("Q").action((v, o) => o.copy(worldHitQueue = Some(v)))
        .text("streamed spheres with hits each candidate lane queues, 0..16, so a sphere with several hits does not " +
          "stall the lane's stream (0: it stalls; world mode only)"),
      opt[Boolean]("world-box-buckets").valueName("true|false").action((v, o) => o.copy(worldBoxBuckets = Some(v)))
        .text("a cell's bucket is its place in the world's box padded by a cell (kept as the table arrives), so no two " +
          "cells share a bucket where the box's places fit the table, and the walk stops at its last place, instead of " +
          "a hash (world mode only)"),
      opt[Boolean]("world-drain-behind").valueName("true|false").action((v, o) => o.copy(worldDrainBehind = Some(v)))
        .text("each candidate lane keeps its chunk's sphere indices in two banks, so the next chunk loads while the last " +
          "one's hits still leave (world mode only)"),
      opt[Int]("world-look-ahead").valueName("A").action((v, o) => o.copy(worldLookAhead = Some(v)))
        .text("visits' bucket ranges each candidate lane looks up ahead of its stream, 3..16 (world mode only; the " +
          "preset has 6)"),
      opt[Boolean]("world-scan-pairs").valueName("true|false").action((v, o) => o.copy(worldScanPairs = Some(v)))
        .text("a coarse chunk's members pair with one another as its scan loads them, and its own 8 cells are not " +
          "visited (world mode with coarse chunks only)"),
      opt[Boolean]("run-queue").valueName("true|false").action((v, o) => o.copy(runQueue = Some(v)))
        .text("a run queue: a start during a run queues one more, and a queued world run's table loads into a " +
          "second on-chip sphere table while the current run computes (world mode only; twice the sphere-table RAM)"),
      opt[Int]("world-line-queue").valueName("Q").action((v, o) => o.copy(worldLineQueue = Some(v)))
        .text("pair lines of candidates queued between the broad phase and the dispatcher, 2..4096 (world mode only; " +
          "deeper lets the lanes run on while a burst of contacts holds the SCPUs)"),
      opt[Boolean]("world-clear-behind").valueName("true|false").action((v, o) => o.copy(worldClearBehind = Some(v)))
        .text("the sort's counters are cleared behind its scatter while the grid reads the bucket ends from tables of " +
          "their own (one table of counters more a sort), so the next world's clear costs no cycle (world mode only)"),
      opt[Boolean]("world-near-filter").valueName("true|false").action((v, o) => o.copy(worldNearFilter = Some(v)))
        .text("a chunk's slots past the large pass's compare the box filter modulo 2^(F+4), exact for the grid's " +
          "neighbouring cells (the default; false keeps every slot's filter on the whole fixed point: more logic, same pairs)"),
      opt[Boolean]("start-ahead").valueName("true|false").action((v, o) => o.copy(startAhead = Some(v)))
        .text("a queued world run's broad phase starts once the current run's is over and its table is in, while the " +
          "current run's last pairs are computed and written (needs the run queue)"),
      opt[String]("scpu-impl").valueName("rtl|model").action((v, o) => o.copy(scpuImpl = Some(v)))
        .text("SCPUs as RTL (default), or for simulation only the C++ SCPU model behind their pipelines " +
          "(same cycles and records, a far faster co-simulation; not synthesizable)"),
      opt[String]("out").valueName("DIR").action((v, o) => o.copy(out = v)).text("parent folder (default generated)"),
      opt[String]("folder").valueName("NAME").action((v, o) => o.copy(folder = Some(v)))
        .text("output folder name (default: the preset's name, or a name derived from every parameter)"),
      opt[Unit]("split").action((_, o) => o.copy(split = true)).text("one .sv file per module (and filelist.f)"),
      opt[Unit]("no-verilog").action((_, o) => o.copy(noVerilog = true)).text("write only manifest.json and the contract headers"),
      opt[String]("device").valueName("NAME").action((v, o) => o.copy(device = Some(v)))
        .text(s"the FPGA part the AFU must fit (${Device.all.map(_.name).mkString(", ")}; default: the preset's)"),
      opt[Unit]("allow-overfit").action((_, o) => o.copy(allowOverfit = true))
        .text("build a configuration that exceeds its device's M20K or DSP blocks (a study; the manifest says so)"),
      opt[Unit]("list-presets").action((_, o) => o.copy(listPresets = true)).text("print the presets and exit"),
      help("help").text("this text"))
  }

  /** The configuration the options ask for, or an error naming the flag and the problem. */
  def config(o: Opts): Either[String, AfuConfig] = {
    def step(flag: String, c: => AfuConfig): Either[String, AfuConfig] =
      try Right(c) catch { case e: IllegalArgumentException => Left(s"$flag: ${e.getMessage.stripPrefix("requirement failed: ")}") }
    def opt[A](flag: String, v: Option[A])(f: (AfuConfig, A) => Either[String, AfuConfig])(c: AfuConfig) =
      v.fold[Either[String, AfuConfig]](Right(c))(a => f(c, a).left.map(m => if (m.startsWith(flag)) m else s"$flag: $m"))
    /** A flag of world mode's: refused unless world mode is built. */
    def worldMode[A](flag: String, v: Option[A])(f: (WorldConfig, A) => WorldConfig)(c: AfuConfig) =
      opt(flag, v)((c, a) => c.world match {
        case Some(w) => step(flag, c.copy(world = Some(f(w, a))))
        case None => Left(s"$flag: world mode is not built (add --world true or --preset world)")
      })(c)
    /** A flag of the broad phase's. */
    def world[A](flag: String, v: Option[A])(f: (BroadPhaseParams, A) => BroadPhaseParams)(c: AfuConfig) =
      worldMode(flag, v)((w, a) => w.copy(broadPhase = f(w.broadPhase, a)))(c)
    // Each flag in turn, in this order (later ones see the earlier ones' choices); the first
    // refusal stops the chain.
    val steps: Seq[AfuConfig => Either[String, AfuConfig]] = Seq(
      opt("--scpu", o.scpu)((c, s) => ScpuConfig.parse(s).flatMap(sc => step("--scpu", c.copy(scpu = sc)))),
      opt("--format", o.format)((c, f) => ScpuConfig.presets.get(f.toLowerCase) match {
        case Some(sc) if o.scpu.isEmpty => step("--format", c.copy(scpu = sc))
        case _ => ScpuConfig.parse(s"${c.scpu.name}:format=$f").flatMap(sc => step("--format", c.copy(scpu = sc)))
      }),
      opt("--tag-bits", o.tagBits)((c, v) => step("--tag-bits", c.copy(tagBits = v,
        maxReadsOutstanding = c.maxReadsOutstanding.min(1 << v.max(1).min(16)),
        maxWritesOutstanding = c.maxWritesOutstanding.min(1 << v.max(1).min(16))))),
      opt("--scpus", o.scpus)((c, v) => step("--scpus", c.copy(scpus = v))),
      opt("--max-spheres", o.maxSpheres)((c, v) => step("--max-spheres", c.copy(maxSpheres = v))),
      opt("--max-reads", o.maxReads)((c, v) => step("--max-reads", c.copy(maxReadsOutstanding = v))),
      opt("--max-writes", o.maxWrites)((c, v) => step("--max-writes", c.copy(maxWritesOutstanding = v))),
      opt("--ram-ports", o.ramPorts)((c, v) => SphereRamPorts.parse(v).flatMap(r => step("--ram-ports", c.copy(ramPorts = r)))),
      opt("--dense-default", o.dense)((c, v) => step("--dense-default", c.copy(denseByDefault = v))),
      opt("--records", o.records)((c, v) => RecordLayout.parse(v).flatMap(r => step("--records", c.copy(records = Some(r))))),
      opt("--world", o.world)((c, v) => step("--world", c.copy(world = if (v) Some(c.world.getOrElse(WorldConfig())) else None))),
      world("--world-lanes", o.worldLanes)((bp, v) => bp.copy(lanes = v,
        sortPorts = BroadPhaseParams.sortPortChoices.filter(_ <= math.min(bp.sortPorts, v)).max)), // ports follow the lanes down
      world("--world-sort-ports", o.worldSortPorts)((bp, v) => bp.copy(sortPorts = v)),
      world("--world-buckets-per-sphere", o.worldBucketsPerSphere) { (bp, v) =>
        require(Seq(1, 2, 4).contains(v), s"must be 1, 2 or 4, got $v")
        bp.copy(bucketsPerSphereLog2 = Seq(1, 2, 4).indexOf(v))
      },
      world("--world-cell-steps", o.worldCellSteps)((bp, v) => bp.copy(cellSteps = v)),
      world("--world-chunk", o.worldChunk)((bp, v) => bp.copy(chunk = v)),
      world("--world-coarse-chunks", o.worldCoarseChunks)((bp, v) => bp.copy(coarseChunks = v,
        scanPairs = bp.scanPairs && v)),
      world("--world-claims", o.worldClaims)((bp, v) => bp.copy(claims = v)),
      world("--world-hit-queue", o.worldHitQueue)((bp, v) => bp.copy(hitQueue = v)),
      world("--world-word-log2", o.worldWordLog2)((bp, v) => bp.copy(wordLog2 = v)),
      world("--world-box-buckets", o.worldBoxBuckets)((bp, v) => bp.copy(boxBuckets = v)),
      opt("--scpu-impl", o.scpuImpl)((c, v) => ScpuImpl.parse(v).flatMap(i => step("--scpu-impl", c.copy(scpuImpl = i)))),
      worldMode("--run-queue", o.runQueue)((w, v) => w.copy(runQueue = v, startAhead = v && w.startAhead)),
      world("--world-drain-behind", o.worldDrainBehind)((bp, v) => bp.copy(drainBehind = v)),
      world("--world-look-ahead", o.worldLookAhead)((bp, v) => bp.copy(lookAhead = v)),
      world("--world-scan-pairs", o.worldScanPairs)((bp, v) => bp.copy(scanPairs = v)),
      worldMode("--world-line-queue", o.worldLineQueue)((w, v) => w.copy(lineQueue = v)),
      worldMode("--start-ahead", o.startAhead)((w, v) => w.copy(startAhead = v)),
      world("--world-clear-behind", o.worldClearBehind)((bp, v) => bp.copy(clearBehind = v)),
      world("--world-near-filter", o.worldNearFilter)((bp, v) => bp.copy(nearFilter = v)),
      opt("--device", o.device)((c, v) => Device.byName(v).left.map(e => s"--device: $e").map(d => c.copy(device = d))),
    )
    AfuConfig.presets.get(o.preset).toRight(
      s"--preset: unknown preset '${o.preset}' (known: ${AfuConfig.all.map(_.name).mkString(", ")})")
      .flatMap(base => steps.foldLeft[Either[String, AfuConfig]](Right(base))((c, f) => c.flatMap(f)))
  }

  val firtoolOpts: Array[String] = Array(
    // Yosys 0.23 reads this: its read_verilog takes a subset of SystemVerilog, without local
    // variables in always blocks or packed arrays (docs/conventions.md, "Tools"); no
    // randomization or source locators, so the output depends on the configuration only.
    "--lowering-options=disallowLocalVariables,disallowPackedArrays,noAlwaysComb",
    "--disable-all-randomization", "--strip-debug-info")

  /** Writes the folder; returns the files written. */
  def generate(cfg: AfuConfig, dir: File, split: Boolean, verilog: Boolean, command: String, allowOverfit: Boolean = false): Seq[File] = {
    // The device: what can be counted before elaboration is checked first, the DSP tiles after.
    def fits(r: AfuResources): Unit = {
      val over = r.overfit(cfg.device)
      if (over.nonEmpty && !allowOverfit)
        throw new IllegalArgumentException(s"it does not fit its device, ${cfg.device.name} (${cfg.device.part}): " +
          over.mkString("; ") + ". Name a larger one (--device), make it smaller, or pass --allow-overfit for a study")
    }
    fits(AfuResources.of(cfg, None)) // M20K: refused before the elaboration, which takes seconds
    val tmp = Files.createTempDirectory("collide-gen").toFile
    def rm(f: File): Unit = { Option(f.listFiles()).foreach(_.foreach(rm)); f.delete() }
    val written = scala.collection.mutable.ArrayBuffer[File]()
    val resources = try {
      val dsp = Option.when(verilog) {
        val args = Array("--target-dir", tmp.getPath) ++ (if (split) Array("--split-verilog") else Array[String]())
        AfuResources.counting(circt.stage.ChiselStage.emitSystemVerilogFile(new Afu(cfg), args, firtoolOpts))._2
      }
      val r = AfuResources.of(cfg, dsp)
      fits(r) // nothing is written for a configuration beyond its part, not even its folder
      dir.mkdirs()
      if (verilog) {
        val svs = tmp.listFiles().filter(f => f.getName.endsWith(".sv") || f.getName.endsWith(".f")).sortBy(_.getName)
        val texts = svs.map(f => f.getName -> new String(Files.readAllBytes(f.toPath), "UTF-8")).toSeq
        val rename = foreignModules(texts.map(_._2), cfg.id)
        for ((name, text) <- texts) {
          val target = new File(dir, uniquify(name, rename))
          writeIfChanged(target, uniquify(text, rename))
          written += target
        }
        // The simulation-only SCPU's Verilog, beside the AFU's (a black box to firtool, which drops
        // inline black-box text when it writes one file).
        if (cfg.scpuImpl == ScpuImpl.Model) {
          val name = ScpuModelUnit.moduleName(cfg.id)
          val target = new File(dir, s"$name.sv")
          writeIfChanged(target, ScpuModelUnit.verilog(cfg.scpu, name))
          written += target
        }
      }
      r
    } finally rm(tmp)
    val manifest = new File(dir, "manifest.json")
    writeIfChanged(manifest, ujson.write(AfuManifest.json(cfg, command, resources), indent = 2) + "\n")
    (written :+ manifest).toSeq ++ writeContract(dir.getAbsoluteFile.getParentFile)
  }

  /** Writes `text` unless the file already holds it: an unchanged Verilog file keeps its time
    * stamp, so builds that depend on it (Verilator) do not run again. */
  def writeIfChanged(f: File, text: String): Unit = {
    val bytes = text.getBytes("UTF-8")
    if (!(f.isFile && java.util.Arrays.equals(Files.readAllBytes(f.toPath), bytes))) Files.write(f.toPath, bytes)
  }

  /** The configuration-independent contract headers, in `parent` (generated/). */
  def writeContract(parent: File): Seq[File] = {
    parent.mkdirs()
    Seq(AfuContract.cppFile -> AfuContract.cpp, AfuContract.svFile -> AfuContract.sv).map { case (n, text) =>
      val f = new File(parent, n)
      writeIfChanged(f, text)
      f
    }
  }

  /** firtool names the modules it makes itself (memories) by shape only; give every module
    * whose name does not carry the configuration's id a suffix, so two configurations never
    * define the same module name differently in one Verilog file. */
  def foreignModules(texts: Seq[String], id: String): Map[String, String] =
    texts.flatMap(t => """(?m)^module\s+(\w+)""".r.findAllMatchIn(t).map(_.group(1)))
      .filterNot(_.contains(id)).distinct.map(n => n -> s"${n}_$id").toMap
  def uniquify(text: String, rename: Map[String, String]): String =
    rename.foldLeft(text) { case (acc, (from, to)) => acc.replaceAll(s"\\b$from\\b", to) }

  def main(args: Array[String]): Unit = {
    val o = scopt.OParser.parse(parser, args, Opts()).getOrElse(sys.exit(2))
    if (o.listPresets) { AfuConfig.all.foreach(c => println(c.describe)); return }
    val cfg = config(o) match {
      case Right(c) => c
      case Left(msg) => System.err.println(s"error: $msg"); sys.exit(2)
    }
    val folder = o.folder.getOrElse(cfg.id)
    val dir = new File(o.out, folder)
    val command = s"""sbt "run ${args.mkString(" ")}""""
    try {
      val files = generate(cfg, dir, o.split, !o.noVerilog, command, o.allowOverfit)
      println(s"${cfg.describe}")
      files.foreach(f => println(s"  wrote ${f.getPath}"))
    } catch {
      case e: Throwable =>
        System.err.println(s"error: configuration ${cfg.id} could not be built: ${e.getMessage}")
        sys.exit(1)
    }
  }
}
