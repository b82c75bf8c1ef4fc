package collide.afu

import collide.scpu.ScpuConfig

/** Everything the host needs to know about one generated AFU, from the one config object:
  * manifest.json (ujson). What does not depend on the configuration is in AfuContract's
  * generated/afu_contract.hpp. */
object AfuManifest {
  /** CCI interface clock of HARP v1 (docs/host.md, link presets). */
  val clockMHz = 200

  /** The manifest without an elaboration: no DSP count. */
  def json(cfg: AfuConfig, command: String): ujson.Obj = json(cfg, command, AfuResources.of(cfg, None))

  def json(cfg: AfuConfig, command: String, resources: AfuResources): ujson.Obj = {
    val p = cfg.puc; val lay = cfg.layout; val s = cfg.scpu
    val overfit = resources.overfit(cfg.device)
    ujson.Obj(
      "name" -> cfg.name, "id" -> cfg.id, "isPreset" -> cfg.isPreset,
      "topModule" -> s"Afu_${cfg.id}",
      "describe" -> cfg.describe,
      "command" -> command,
      "afu" -> ujson.Obj(
        "scpus" -> cfg.scpus, "maxSpheres" -> cfg.maxSpheres,
        "maxReadsOutstanding" -> cfg.maxReadsOutstanding, "maxWritesOutstanding" -> cfg.maxWritesOutstanding,
        "tagBits" -> cfg.tagBits, "ramPorts" -> cfg.ramPorts.name, "denseByDefault" -> cfg.denseByDefault,
        "lanes" -> p.lanes, "peakPairsPerCycle" -> cfg.peakPairsPerCycle,
        "pairLatency" -> cfg.pairLatency, "pairBufferLines" -> p.pairBufferLines,
        "groupsInFlight" -> p.groupsInFlight, "scpuQueueDepth" -> p.scpuQueueDepth,
        "writeQueueLines" -> p.writeQueueLines,
        "pairKinds" -> cfg.pairKinds,
        "world" -> cfg.world.isDefined,
        "runQueue" -> cfg.runQueue, "sphereTables" -> p.tables,
        "broadPhase" -> cfg.world.map { w =>
          val bp = w.broadPhase
          ujson.Obj("largeMax" -> bp.largeMax, "cellBits" -> bp.cellBits, "bucketsLog2" -> bp.bucketsLog2,
            "margin" -> s"${bp.marginNum}/${bp.marginDen}", "cellOverError" -> bp.cellOverError,
            "filterFracBits" -> bp.filterFracBits, "chunk" -> bp.chunk, "wordLog2" -> bp.wordLog2,
            "lanes" -> bp.lanes, "sortPorts" -> bp.sortPorts, "bucketsPerSphereLog2" -> bp.bucketsPerSphereLog2,
            "cellSteps" -> bp.cellSteps, "coarseChunks" -> bp.coarseChunks, "team" -> bp.teamSize, "claims" -> bp.claims, "hitQueue" -> bp.hitQueue, "boxBuckets" -> bp.boxBuckets,
            "drainBehind" -> bp.drainBehind, "lookAhead" -> bp.lookAhead, "scanPairs" -> bp.scanPairs,
            "clearBehind" -> bp.clearBehind, "nearFilter" -> bp.nearFilter, "lineQueue" -> w.lineQueue, "startAhead" -> w.startAhead,
            "recordPair" -> s"i | j << ${RecordTag.WORLD_INDEX_BITS}")
        }.getOrElse(ujson.Null),
        "ram" -> ujson.Obj("copies" -> p.ramCopies, "banks" -> p.banks, "bitsPerCopy" -> p.ramBitsPerCopy.toDouble,
          "sphereTableM20k" -> p.ramM20k.toDouble,
          "sphereTableBits" -> p.ramBits.toDouble, "pairBufferBits" -> p.pairBufferBits.toDouble,
          "broadPhaseBits" -> ujson.Num(cfg.broadPhase.map(_.ramBits(cfg.maxSpheres).toDouble).getOrElse(0.0)),
          "broadPhaseM20k" -> p.broadPhaseM20k.toDouble)),
      "device" -> ujson.Obj("name" -> cfg.device.name, "part" -> cfg.device.part, "alms" -> cfg.device.alms,
        "m20k" -> cfg.device.m20k, "dspBlocks" -> cfg.device.dspBlocks, "source" -> cfg.device.source,
        "utilization" -> resources.json(cfg.device), "fits" -> overfit.isEmpty,
        "overfit" -> ujson.Arr.from(overfit.map(ujson.Str))),
      "scpu" -> { val o = scpuJson(s); o("impl") = cfg.scpuImpl.name; o },
      "link" -> ujson.Obj(
        "format" -> AfuContract.linkName(cfg.scpu.linkFormat), "width" -> cfg.linkWidth,
        "expBits" -> cfg.scpu.linkFormat.expBits, "sigBits" -> cfg.scpu.linkFormat.sigBits,
        "lineBytes" -> Link.lineBytes, "addrBits" -> Link.addrBits, "clockMHz" -> clockMHz,
        "maxReads" -> cfg.maxReadsOutstanding, "maxWrites" -> cfg.maxWritesOutstanding, "tagBits" -> cfg.tagBits),
      "buffers" -> ujson.Obj(
        "sphereBytes" -> lay.sphereBytes, "spheresPerLine" -> lay.spheresPerLine,
        "pairBytes" -> lay.pairBytes, "pairsPerLine" -> lay.pairsPerLine,
        "recordBytes" -> lay.recordBytes, "recordsPerLine" -> lay.recordsPerLine,
        "recordPairIndexBit" -> lay.pairIndexBit.map(ujson.Num(_)).getOrElse(ujson.Null), "recordFlagsBit" -> lay.flagsBit,
        "pairIndexBits" -> lay.pairIndexBits, "maxPairs" -> lay.maxPairs.toDouble,
        "recordFlags" -> ujson.Obj.from(RecordFlags.all.map { case (k, v) => k -> ujson.Num(v) }),
        "records" -> ujson.Obj("layout" -> cfg.recordLayout.name, "code" -> cfg.recordLayout.code,
          "fields" -> ujson.Arr.from(cfg.recordLayout.fields.map(ujson.Str)), "masked" -> lay.masked,
          "recordBits" -> lay.recordBits, "recordBytes" -> lay.recordBytes, "recordsPerLine" -> lay.recordsPerLine,
          "groupPairs" -> p.lanes)),
      "csr" -> ujson.Obj.from(Csr.all.map { case (k, v) => k -> ujson.Num(v) }),
      "csrValues" -> ujson.Obj("CTRL_START" -> Csr.CTRL_START, "MODE_DENSE" -> Csr.MODE_DENSE, "MODE_WORLD" -> Csr.MODE_WORLD),
      "status" -> ujson.Obj.from(StatusLine.all.map { case (k, v) => k -> ujson.Num(v) }),
      "statusNoBadPair" -> StatusLine.NO_BAD_PAIR.toDouble,
      "errorFlags" -> ujson.Obj.from(ErrorFlags.all.map { case (k, v) => k -> ujson.Num(v) }))
  }

  def scpuJson(s: ScpuConfig): ujson.Obj = ujson.Obj(
    "name" -> s.name, "id" -> s.id, "describe" -> s.describe,
    "format" -> ujson.Obj("name" -> s.format.name, "expBits" -> s.format.expBits, "sigBits" -> s.format.sigBits),
    "subnormals" -> s.subnormals, "rounding" -> s.rounding.toString, "distance" -> s.distance.name,
    "sqrtAlg" -> s.sqrtAlg.name, "recipAlg" -> s.recipAlg.name, "rsqrtAlg" -> s.rsqrtAlg.name,
    "latency" -> s.latency,
    "latencies" -> ujson.Obj("cvt" -> s.cvtLat, "add" -> s.addLatency, "mul" -> s.mulLatency, "cmp" -> s.cmpLatency,
      "sqrt" -> s.sqrtLat, "recip" -> s.recipLat, "rsqrt" -> s.rsqrtLat, "scale" -> s.scaleLatency,
      "in" -> s.inLatency, "core" -> s.coreLatency, "out" -> s.outLatency),
    "tagBits" -> s.tagBits)
}
