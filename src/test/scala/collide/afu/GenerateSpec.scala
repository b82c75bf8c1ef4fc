package collide.afu

import org.scalatest.flatspec.AnyFlatSpec
import collide.Generate

/** The generator CLI's configuration handling, manifest and header (no hardware built). */
class GenerateSpec extends AnyFlatSpec {
  behavior of "collide.Generate"

  private def cfg(args: String*) =
    scopt.OParser.parse(Generate.parser, args, Generate.Opts()).map(Generate.config).getOrElse(fail(s"parse: $args"))

  it should "build the presets and name derived configurations by every parameter" in {
    assert(cfg().contains(AfuConfig.default))
    assert(cfg("--preset", "fp16").contains(AfuConfig.fp16))
    val c = cfg("--scpus", "4", "--format", "fp16").toOption.get
    assert(c.scpus == 4 && c.scpu.format == collide.fp.FloatFormat.fp16 && !c.isPreset)
    assert(c.id == "n4_fp16_s1024_r64_w64_t6_rep")
    val d = cfg("--scpus", "4", "--format", "fp16", "--max-spheres", "2048").toOption.get
    assert(d.id != c.id && d.puc.name != c.puc.name, "two configurations must not share module names")
    assert(cfg("--format", "e6m12").toOption.get.scpu.format == collide.fp.FloatFormat(6, 12))
    assert(cfg("--scpu", "fp32:rm=rtz").toOption.get.scpu.rounding == collide.fp.RoundingMode.RTZ)
    val w = cfg("--scpus", "4", "--world", "true").toOption.get
    assert(w.world.contains(WorldConfig()) && w.recordLayout == RecordLayout.Derived && w.id.endsWith("_world"),
      s"world mode on: ${w.id}, ${w.recordLayout.name} records (a world record names its spheres: indexed)")
    assert(cfg("--preset", "world").contains(AfuConfig.world))
    assert(cfg("--preset", "world", "--world", "false").toOption.get.world.isEmpty)
    // 2^13 buckets of 13-bit counters and 4096 entries of a 12-bit index and a mark
    assert(collide.world.BroadPhaseParams.default.ramBits(4096) == 8192L * 13 + 4096L * 13)
    // The world preset's 16 lanes and eight sort ports: four sorts (groups), each of a quarter
    // of the table: per group and lane a table of 8192 11-bit counters and 1024 entries of a
    // 12-bit index and a mark, and per group a table of counters more for its second port; a
    // sphere copy per two lanes.
    val group16 = (16 + 1) * 8192L * 11 + 16 * 1024L * 13
    assert(AfuManifest.json(AfuConfig.world, "")("afu")("ram")("broadPhaseBits").num == 4.0 * group16)
    // In M20K blocks: a table of counters is 256 words of 32 x 11 = 352 bits, nine 512 x 40
    // blocks (one write, one read); 1024 entries of 13 bits, written by both ports, one 1K x 20.
    assert(AfuManifest.json(AfuConfig.world, "")("afu")("ram")("broadPhaseM20k").num == 4.0 * (17 * 9 + 16 * 1))
    // 16 ports: eight sorts; 10-bit counters, 320 bits a word: eight blocks a table (1,088 for the counters).
    assert(cfg("--preset", "world", "--world-sort-ports", "16").toOption.get.puc.broadPhaseM20k == 8 * (17 * 8 + 16 * 1))
    // world32: 32 lanes and a table of cursors more a sort (cleared behind).
    assert(AfuConfig.world32.puc.broadPhaseM20k == 8 * (34 * 8 + 32 * 1))
    // Four sort ports: two sorts of half the table (12-bit counters, 2048 entries).
    val p4 = cfg("--preset", "world", "--world-sort-ports", "4").toOption.get
    assert(p4.id.endsWith("_world16p4w5e2k32xuh8bxda6sp") && p4.broadPhase.get.ramBits(4096) == 2 * ((16 + 1) * 8192L * 12 + 16 * 2048L * 13), p4.id)
    assert(AfuConfig.world.puc.ramCopies == 16 + 8, "sixteen SCPU copies and the broad phase's eight")
    // Lanes: a sort RAM each, a sphere copy per two; a name of their own.
    val l5 = cfg("--preset", "world", "--world-lanes", "5").toOption.get
    assert(l5.broadPhase.get.lanes == 5 && l5.id.endsWith("_world5p4w5e2k32xuh8bxda6sp") && l5.puc.ramCopies == 16 + 3, s"five lanes: ${l5.id}, ${l5.puc.ramCopies} copies")
    assert(l5.broadPhase.get.ramBits(4096) == 2 * ((5 + 1) * 8192L * 12 + 5 * 2048L * 13))
    // Fewer lanes than the ports: the ports follow down to the most a configuration allows.
    val l3 = cfg("--preset", "world", "--world-lanes", "3").toOption.get
    assert(l3.broadPhase.get.sortPorts == 2 && l3.id.endsWith("_world3p2w5e2k32xuh8bxda6sp") && l3.broadPhase.get.ramBits(4096) == 3 * 159744L + 8192 * 13, l3.id)
    // One bucket a sphere: half the counters (4096 of 12 bits per group and lane) and a name of its own.
    val b1 = cfg("--preset", "world", "--world-buckets-per-sphere", "1").toOption.get
    assert(b1.id.endsWith("_world16p8w5s0e2k32xuh8bxda6sp") && b1.broadPhase.get.ramBits(4096) == 4 * ((16 + 1) * 4096L * 11 + 16 * 1024L * 13), b1.id)
    // The preset's grid: chunks of 32, coarse chunks, edges of 1.5 * 2^k too.
    val pw = AfuConfig.world.broadPhase.get
    assert(pw.cellSteps == 2 && pw.chunk == 32 && pw.coarseChunks && pw.claims && pw.teamSize == 1, s"the preset's grid: $pw")
    // Edges of 2^k alone: a name of its own, the same RAM.
    val e1 = cfg("--preset", "world", "--world-cell-steps", "1").toOption.get
    assert(e1.broadPhase.get.cellSteps == 1 && e1.id.endsWith("_world16p8w5k32xuh8bxda6sp") && e1.broadPhase.get.ramBits(4096) == pw.ramBits(4096), e1.id)
    // The grid before coarse chunks: chunks of 16 cells, edges 2^k; the same RAM.
    val x = cfg("--preset", "world", "--world-chunk", "16", "--world-coarse-chunks", "false", "--world-cell-steps", "1").toOption.get
    assert(!x.broadPhase.get.coarseChunks && x.broadPhase.get.chunk == 16 && x.id.endsWith("_world16p8w5uh8bxda6") && x.broadPhase.get.ramBits(4096) == pw.ramBits(4096), x.id)
    // Without claims, teams: the largest power of two up to 4 that divides the lanes; a name of its own.
    val t6 = cfg("--preset", "world", "--world-lanes", "6", "--world-claims", "false").toOption.get
    assert(t6.broadPhase.get.teamSize == 2 && t6.id.endsWith("_world6p4w5e2k32xh8bxda6sp"), t6.id)
    assert(cfg("--preset", "world", "--world-claims", "false").toOption.get.broadPhase.get.teamSize == 4)
    val p1 = cfg("--preset", "world", "--world-lanes", "5", "--world-sort-ports", "1").toOption.get
    assert(p1.broadPhase.get.sortPorts == 1 && p1.id.endsWith("_world5w5e2k32xuh8bxda6sp") && p1.broadPhase.get.ramBits(4096) == 5 * 159744L, p1.id)
    assert(cfg("--world", "true", "--world-lanes", "5", "--world-sort-ports", "2").toOption.get.id.endsWith("_world5p2"),
      "eight counters a word (the default): no word size in the name")
    assert(cfg("--preset", "world", "--world-lanes", "16").toOption.get.isPreset)
    // Hits queued eight spheres deep in the preset; without a queue, a name without the h.
    assert(pw.hitQueue == 8 && pw.wordLog2 == 5, s"the preset's queue and word: $pw")
    assert(cfg("--preset", "world", "--world-hit-queue", "0").toOption.get.id.endsWith("_world16p8w5e2k32xubxda6sp"))
    // 16 counters a word: the same RAM bits, a name of its own.
    val w4 = cfg("--preset", "world", "--world-word-log2", "4").toOption.get
    assert(w4.id.endsWith("_world16p8w4e2k32xuh8bxda6sp") && w4.broadPhase.get.ramBits(4096) == pw.ramBits(4096), w4.id)
    assert(AfuManifest.json(AfuConfig.world, "")("afu")("broadPhase")("hitQueue").num == 8)
    // Draining behind and six visits looked up ahead in the preset; without, names of their own.
    assert(pw.drainBehind && pw.lookAhead == 6, s"the preset's drain and look-ahead: $pw")
    assert(cfg("--preset", "world", "--world-drain-behind", "false", "--world-look-ahead", "3", "--world-scan-pairs", "false").toOption.get.id.endsWith("_world16p8w5e2k32xuh8bx"))
    // Pairs in the scan in the preset; they need coarse chunks.
    assert(pw.scanPairs && AfuManifest.json(AfuConfig.world, "")("afu")("broadPhase")("scanPairs").bool)
    assert(cfg("--preset", "world", "--world-coarse-chunks", "false", "--world-scan-pairs", "true").isLeft,
      "scan pairs without coarse chunks are refused (without coarse chunks the preset drops them)")
    assert(AfuManifest.json(AfuConfig.world, "")("afu")("broadPhase")("lookAhead").num == 6)
    assert(cfg("--preset", "world", "--world-look-ahead", "2").isLeft, "a look-ahead below three is refused")
    // 16 sort ports: eight sorts of an eighth of the table, eight tables of 10-bit counters a lane.
    val p16 = cfg("--preset", "world", "--world-sort-ports", "16").toOption.get
    assert(p16.id.endsWith("_world16p16w5e2k32xuh8bxda6sp") && p16.broadPhase.get.sortGroups == 8 &&
      p16.broadPhase.get.ramBits(4096) == 8 * ((16 + 1) * 8192L * 10 + 16 * 512L * 13), p16.id)
    // Box buckets in the preset; a hashed table is a name of its own with the same RAM bits.
    val hb = cfg("--preset", "world", "--world-box-buckets", "false").toOption.get
    assert(pw.boxBuckets && hb.id.endsWith("_world16p8w5e2k32xuh8da6sp") && hb.broadPhase.get.ramBits(4096) == pw.ramBits(4096), hb.id)
    assert(AfuManifest.json(AfuConfig.world, "")("afu")("broadPhase")("boxBuckets").bool)
    assert(cfg("--preset", "world", "--world-lanes", "1").toOption.get.id.endsWith("_worldw5e2k32xuh8bxda6sp"),
      "one lane: no lane count in the name, and the sort's ports follow the lanes down to one")
    // The run queue in the preset: every sphere-table RAM twice (a table each), the same copies;
    // without it a name of its own and half the sphere-table bits; it goes with world mode.
    val nq = cfg("--preset", "world", "--run-queue", "false").toOption.get
    assert(AfuConfig.world.runQueue && AfuConfig.world.puc.tables == 2 && !nq.runQueue && nq.puc.tables == 1)
    assert(nq.id.contains("_rep_world") && cfg("--preset", "world", "--world-lanes", "5").toOption.get.id.contains("_rep_q_world"), nq.id)
    assert(AfuConfig.world.puc.ramBits == 2 * nq.puc.ramBits && AfuConfig.world.puc.ramCopies == nq.puc.ramCopies)
    assert(AfuConfig.world.puc.ramM20k == 2 * nq.puc.ramM20k, "a second table is a second RAM beside each (never three ports on one)")
    val mq = AfuManifest.json(AfuConfig.world, "")("afu")
    assert(mq("runQueue").bool && mq("sphereTables").num == 2 && !AfuManifest.json(nq, "")("afu")("runQueue").bool)
    assert(!cfg("--preset", "world", "--world", "false").toOption.get.runQueue, "no world mode, no run queue")
    // Starting queued broad phases ahead and a deeper line queue: names of their own, in the
    // manifest; 32 lanes (past a line's 16 candidates) are built.
    val sa = cfg("--preset", "world", "--world-lanes", "32", "--world-sort-ports", "16", "--world-line-queue", "64", "--start-ahead", "true").toOption.get
    assert(sa.world.get.startAhead && sa.world.get.lineQueue == 64 && sa.broadPhase.get.lanes == 32 && sa.id.endsWith("_world32p16w5e2k32xuh8bxda6spl64z"), sa.id)
    assert(sa.puc.world.get.startAhead && sa.puc.world.get.lineQueue == 64)
    val ms = AfuManifest.json(sa, "")("afu")("broadPhase")
    assert(ms("startAhead").bool && ms("lineQueue").num == 64 && ms("lanes").num == 32)
    // The world32 preset is the world preset with exactly these flags, on the Arria 10 it studies.
    val w32 = cfg("--preset", "world", "--world-lanes", "32", "--world-sort-ports", "16", "--world-line-queue", "256",
      "--start-ahead", "true", "--world-clear-behind", "true", "--device", "10AX115").toOption.get
    assert(w32.copy(name = "world32") == AfuConfig.world32 && cfg("--preset", "world32").toOption.get.id == "world32")
    assert(AfuConfig.world32.puc.ramCopies == 16 + 16, "sixteen SCPU copies and the 32 lanes' sixteen")
    // Counters cleared behind the scatter: one table of counters more a sort, a name of its own.
    val cb = cfg("--preset", "world", "--world-clear-behind", "true").toOption.get
    assert(cb.id.endsWith("_world16p8w5e2k32xuh8bxda6spcb") && AfuManifest.json(cb, "")("afu")("broadPhase")("clearBehind").bool, cb.id)
    assert(cb.broadPhase.get.ramBits(4096) - pw.ramBits(4096) == 4L * 8192 * 11, "a table of 2^13 11-bit counters more in each of the four sorts")
    // The near filter is the default; off, a name of its own, the same RAM.
    assert(AfuConfig.world.broadPhase.get.nearFilter && AfuManifest.json(AfuConfig.world, "")("afu")("broadPhase")("nearFilter").bool)
    val wf = cfg("--preset", "world", "--world-near-filter", "false").toOption.get
    assert(wf.id.endsWith("_world16p8w5e2k32xuh8bxda6spwf") && !AfuManifest.json(wf, "")("afu")("broadPhase")("nearFilter").bool, wf.id)
    assert(wf.broadPhase.get.ramBits(4096) == pw.ramBits(4096))
  }

  it should "refuse a configuration that cannot be built, naming the flag and the problem" in {
    def err(args: String*)(flag: String, words: String*) = {
      val e = cfg(args: _*)
      assert(e.isLeft, s"$args should fail")
      val m = e.swap.toOption.get
      assert(m.startsWith(flag) && words.forall(m.contains), s"message '$m' should start with $flag and say ${words.mkString(", ")}")
    }
    err("--scpus", "0")("--scpus", "1..64")
    err("--preset", "world", "--world-hit-queue", "17")("--world-hit-queue", "0..16")
    err("--preset", "world", "--world-word-log2", "2")("--world-word-log2", "coarseChunks needs wordLog2 >= 3")
    err("--preset", "world", "--world-word-log2", "6")("--world-word-log2", "0..5")
    err("--world-hit-queue", "4")("--world-hit-queue", "world mode is not built")
    err("--world-box-buckets", "true")("--world-box-buckets", "world mode is not built")
    err("--world-near-filter", "false")("--world-near-filter", "world mode is not built")
    err("--run-queue", "true")("--run-queue", "world mode is not built")
    err("--preset", "world", "--run-queue", "false", "--start-ahead", "true")("--start-ahead", "needs the run queue")
    err("--preset", "world", "--world-line-queue", "1")("--world-line-queue", "2..4096")
    err("--world-line-queue", "8")("--world-line-queue", "world mode is not built")
    err("--scpus", "65")("--scpus", "1..64")
    err("--max-spheres", "1000")("--max-spheres", "power of two")
    err("--max-reads", "65")("--max-reads", "2^tagBits")
    err("--preset", "nope")("--preset", "unknown")
    err("--format", "e20m5")("--format", "exponent")
    err("--scpu", "fp32:tag=8")("--scpu", "tagBits")
    err("--ram-ports", "crossbar")("--ram-ports", "crossbar", "banked")
    err("--ram-ports", "banked:3")("--ram-ports", "power of two")
    err("--ram-ports", "banked:2")("--ram-ports", "4 spheres of a line")
    err("--ram-ports", "banked:4", "--format", "fp16")("--ram-ports", "8 spheres of a line")
    err("--world", "true", "--max-spheres", "8192")("--world", "4096")
    err("--preset", "world", "--max-spheres", "8192")("--max-spheres", "4096")
    err("--world", "true", "--records", "derived-masked")("--world", "indexed")
    err("--world", "true", "--format", "fp24")("--world", "converts")
    err("--world-lanes", "4")("--world-lanes", "not built")
    err("--preset", "world", "--world-lanes", "33")("--world-lanes", "1..32")
    err("--world-sort-ports", "2")("--world-sort-ports", "not built")
    err("--preset", "world", "--world-sort-ports", "3")("--world-sort-ports", "1, 2, 4, 8 or 16")
    err("--world", "true", "--world-sort-ports", "2")("--world-sort-ports", "at most lanes")
    err("--preset", "world", "--world-buckets-per-sphere", "3")("--world-buckets-per-sphere", "1, 2 or 4")
    err("--world-buckets-per-sphere", "1")("--world-buckets-per-sphere", "not built")
    err("--preset", "world", "--world-cell-steps", "3")("--world-cell-steps", "1 (edges 2^k) or 2")
    err("--world-cell-steps", "2")("--world-cell-steps", "not built")
    err("--preset", "world", "--world-chunk", "0")("--world-chunk", "chunk must be 1..256")
    err("--world-chunk", "32")("--world-chunk", "not built")
    err("--world-coarse-chunks", "true")("--world-coarse-chunks", "not built")
  }

  it should "build the SCPUs as the C++ model for co-simulation only where the model reproduces them, saying why not elsewhere" in {
    val m = cfg("--scpu-impl", "model").toOption.get
    assert(m.scpuImpl == collide.scpu.ScpuImpl.Model && m.id.endsWith("_model") && m.id != AfuConfig.default.id,
      s"a model AFU's modules must not share the RTL one's names: ${m.id}")
    assert(cfg("--preset", "cosim").contains(AfuConfig.cosim))
    assert(AfuManifest.json(AfuConfig.cosim, "")("scpu")("impl").str == "model")
    assert(AfuManifest.json(AfuConfig.default, "")("scpu")("impl").str == "rtl")
    for (f <- Seq("fp16", "bf16", "fp24", "fp64")) assert(cfg("--scpu-impl", "model", "--format", f).isRight, f)
    assert(cfg("--scpu-impl", "model", "--scpu", "fp32-robust").isRight)
    def err(args: String*)(words: String*) = {
      val e = cfg(args: _*)
      assert(e.isLeft, s"$args should fail")
      val msg = e.swap.toOption.get
      assert(msg.startsWith("--scpu-impl") && words.forall(msg.contains), s"'$msg' should name --scpu-impl and say ${words.mkString(", ")}")
    }
    err("--scpu-impl", "c++")("rtl or model")
    err("--scpu-impl", "model", "--scpu", "fp32-nr")("not correctly rounded")
    err("--scpu-impl", "model", "--scpu", "fp32-rsqrt-dr")("rsqrt")
    err("--scpu-impl", "model", "--scpu", "fp32:rm=rtz")("RTZ")
    err("--scpu-impl", "model", "--scpu", "fp32:subnormals=false")("flushes")
    err("--scpu-impl", "model", "--format", "e11m40")("2p + 2")
    // Its Verilog: the pipeline of the SCPU's latency around the DPI-C import
    val v = collide.scpu.ScpuModelUnit.verilog(collide.scpu.ScpuConfig.fp32, "ScpuModel_x")
    assert(v.contains("module ScpuModel_x(") && v.contains("import \"DPI-C\" function void collide_scpu_model(") &&
      v.contains(s"reg [${collide.scpu.ScpuConfig.fp32.latency - 1}:0] valid_q;"), v.take(400))
  }

  it should "bank the sphere table instead of copying it per SCPU, and say what each costs in RAM" in {
    val rep = AfuConfig.default.copy(maxSpheres = 65536)
    val bank = cfg("--max-spheres", "65536", "--ram-ports", "banked").toOption.get
    assert(bank.ramPorts == SphereRamPorts.Banked() && bank.id == "n16_fp32_200_s65536_r64_w64_t6_bank")
    assert(bank.puc.banks == 32 && bank.puc.ramCopies == 1 && rep.puc.ramCopies == 16)
    assert(bank.puc.ramBits == 65536L * 128 && rep.puc.ramBits == 16 * 65536L * 128)
    // 64k fp32 spheres: 32 banks of 2K x 128 bits, 13 M20Ks each (2K x 10 mode), fit a
    // 5SGXEA7's 2,560 blocks; sixteen line-wide copies (16K x 512) take 412 each and do not.
    assert(bank.puc.ramM20k == 32 * 13 && rep.puc.ramM20k == 16 * 412)
    assert(bank.puc.ramM20k < M20k.deviceBlocks && rep.puc.ramM20k > M20k.deviceBlocks)
    val m = AfuManifest.json(bank, "")("afu")("ram")
    assert(m("banks").num == 32 && m("copies").num == 1 && m("sphereTableM20k").num == 416)
    // Fewer SCPUs, fewer banks (two reads a pair, two ports a bank): 4 SCPUs, 8 banks.
    assert(cfg("--scpus", "4", "--ram-ports", "banked").toOption.get.puc.banks == 8)
    assert(cfg("--scpus", "1", "--format", "fp16", "--ram-ports", "banked").toOption.get.puc.banks == 8, "a line's 8 spheres")
    assert(cfg("--ram-ports", "banked:64").toOption.get.puc.banks == 64)
    assert(cfg("--preset", "world", "--ram-ports", "banked").toOption.get.puc.ramCopies == 1 + 8, "the SCPUs' copy and the broad phase's eight (16 lanes)")
  }

  it should "pick the link format from the compute format, or the one asked for" in {
    import collide.fp.FloatFormat
    assert(cfg("--format", "fp16").toOption.get.scpu.linkFormat == FloatFormat.fp16)
    assert(cfg("--format", "bf16").toOption.get.scpu.linkFormat == FloatFormat.bf16)
    assert(cfg("--format", "fp24").toOption.get.scpu.linkFormat == FloatFormat.fp32)
    assert(cfg("--format", "fp64").toOption.get.scpu.linkFormat == FloatFormat.fp64)
    assert(cfg("--scpu", "fp16:link=fp32").toOption.get.layout.sphereBytes == 16)
    assert(cfg("--scpu", "fp16").toOption.get.layout.spheresPerLine == 8)
    val e = cfg("--scpu", "fp32:link=fp16")
    assert(e.isLeft && e.swap.toOption.get.contains("does not hold every fp32 value"), e.toString)
  }

  it should "default to derived records where the host rebuilds them exactly, masked where that fits more a line, and refuse derived elsewhere, saying why" in {
    assert(AfuConfig.default.recordLayout == RecordLayout.DerivedMasked)    // 7 a line, not 5
    assert(AfuConfig.fp16.recordLayout == RecordLayout.DerivedMasked)       // 12, not 8
    assert(AfuConfig.fp64.recordLayout == RecordLayout.Derived)             // 3 either way
    assert(AfuConfig.paper.recordLayout == RecordLayout.Full)
    assert(cfg("--scpu", "fp32:rm=rtz").toOption.get.recordLayout == RecordLayout.Full)          // 2 either way
    assert(cfg("--scpu", "fp16:rm=rtz").toOption.get.recordLayout == RecordLayout.FullMasked)    // 4, not 3
    assert(cfg("--records", "full").toOption.get.layout.recordBytes == 32)
    def refused(args: String*)(why: String) = {
      val e = cfg(args: _*)
      assert(e.isLeft, s"$args should fail")
      val m = e.swap.toOption.get
      assert(m.startsWith("--records") && m.contains("derived") && m.contains(why), m)
    }
    refused("--scpu", "fp32:rm=rtz", "--records", "derived")("RNE")
    refused("--scpu", "fp32:subnormals=off", "--records", "derived")("subnormals")
    refused("--format", "e8m30", "--records", "derived")("2p+2")
    refused("--format", "e8m30", "--records", "derived-masked")("2p+2")
    assert(cfg("--format", "e8m30", "--records", "full-masked").toOption.get.recordLayout == RecordLayout.FullMasked)
    assert(cfg("--records", "masked").swap.toOption.get.contains("expected one of full, derived, full-masked, derived-masked"))
  }

  it should "size records from the layout and the link width" in {
    // (link width, layout) -> (record bytes, records a line); masked: the flags byte replaces the tag word
    val want = Map((16, RecordLayout.Full) -> (18, 3), (16, RecordLayout.Derived) -> (8, 8),
      (32, RecordLayout.Full) -> (32, 2), (32, RecordLayout.Derived) -> (12, 5),
      (64, RecordLayout.Full) -> (60, 1), (64, RecordLayout.Derived) -> (20, 3),
      (16, RecordLayout.FullMasked) -> (15, 4), (16, RecordLayout.DerivedMasked) -> (5, 12),
      (32, RecordLayout.FullMasked) -> (29, 2), (32, RecordLayout.DerivedMasked) -> (9, 7),
      (64, RecordLayout.FullMasked) -> (57, 1), (64, RecordLayout.DerivedMasked) -> (17, 3))
    for (((w, l), (bytes, per)) <- want) {
      val b = BufferLayout(w, l)
      assert(b.recordBytes == bytes && b.recordsPerLine == per, s"$w $l: ${b.recordBytes} B, ${b.recordsPerLine} a line")
      if (l.masked) assert(b.pairIndexBit.isEmpty && b.flagsBit == l.fields.size * w && b.recordBits >= MaskHeader.BITS)
      else assert(b.pairIndexBit.contains(l.fields.size * w) && b.flagsBit == l.fields.size * w + 24)
    }
  }

  it should "write every CSR, status offset and flag into the manifest and the contract headers" in {
    val c = AfuConfig.fp64.copy(scpus = 3)
    val m = AfuManifest.json(c, "cmd")
    val h = AfuContract.cpp; val sv = AfuContract.sv
    for ((k, v) <- Csr.all) {
      assert(m("csr")(k).num == v); assert(h.contains(s"CSR_$k = ${v}u;")); assert(sv.contains(s"AFU_CSR_$k = $v;"))
    }
    for ((k, v) <- StatusLine.all) { assert(m("status")(k).num == v); assert(h.contains(s"STATUS_$k = ${v}u;")) }
    for ((k, v) <- ErrorFlags.all) { assert(h.contains(s"ERR_$k = ${v}u;")); assert(sv.contains(s"AFU_ERR_$k = $v;")) }
    for ((k, v) <- RecordFlags.all) assert(h.contains(s"REC_$k = ${v}u;"))
    for (l <- RecordLayout.all) assert(h.contains(s"LAYOUT_${AfuContract.constName(l)} = ${l.code}u;"))
    for (e <- MaskHeader.entries) assert(h.contains(s"HEADER_${e.name} = ${e.value}u;"))
    assert(m("link")("format").str == "binary64" && m("buffers")("recordsPerLine").num == 3 && m("buffers")("spheresPerLine").num == 2)
    assert(m("buffers")("records")("layout").str == "derived" && m("buffers")("records")("fields").arr.map(_.str) == Seq("d", "w"))
    assert(m("afu")("ram")("sphereTableBits").num == 3.0 * 1024 * 4 * 64)
    assert(m("scpu")("latency").num == c.scpu.latency)
  }
}
