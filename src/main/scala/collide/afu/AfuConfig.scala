package collide.afu

import collide.scpu.{ScpuConfig, ScpuImpl}

/** One AFU configuration: the SCPUs it holds and the PUC around them. Every field has a
  * default; the default is the `default` preset (16 fp32 correctly rounded SCPUs, each operator
  * pipelined for 200 MHz: ScpuConfig.fp32At200).
  *
  * @param name                 preset name (the output folder and the module names' suffix
  *                             when the configuration is exactly that preset)
  * @param scpus                SCPUs (1..64); pairs dispatched per cycle = min(scpus, 16)
  * @param scpu                 the SCPU configuration (format, rounding, algorithms, latencies)
  * @param maxSpheres           on-chip sphere table entries (the paper's diamond at hMax 10
  *                             has 670 spheres); a larger NUM_SPHERES is refused (error bit 1)
  * @param maxReadsOutstanding  read requests in flight at most (SPL's 6-bit tags: 64)
  * @param maxWritesOutstanding write requests in flight at most (64)
  * @param tagBits              link tag width (HARP v1 / SPL: 6, docs/afu-interface.md)
  * @param ramPorts             sphere table read ports: a copy per SCPU (replicated) or one copy
  *                             in banks, two read ports each (banked; conflicts cost cycles)
  * @param denseByDefault       reset value of MODE bit 0 (false: compact records)
  * @param records              contact record layout; None = the best one offered for the SCPU
  *                             (AfuConfig.bestLayout: derived where the host can rebuild contacts
  *                             exactly, else full; masked where that fits more a line, except
  *                             with world mode, whose records name their spheres)
  * @param world                build world mode (MODE bit 1): an on-chip broad phase finds the
  *                             pairs (WorldConfig: the broad phase, the run queue, the line queue,
  *                             starting ahead); None = pair lists only
  * @param device               the FPGA part it must fit (Device; the generator refuses a
  *                             configuration whose M20K blocks or DSP tiles exceed it unless
  *                             --allow-overfit)
  * @param scpuImpl             how the SCPUs are built: RTL, or (simulation only) the C++ SCPU
  *                             model behind a pipeline of the SCPU's latency (ScpuModelUnit): the
  *                             same cycles and records, a far cheaper co-simulation
  */
final case class AfuConfig(
    name: String = "default",
    scpus: Int = 16,
    scpu: ScpuConfig = ScpuConfig.fp32At200,
    maxSpheres: Int = 1024,
    maxReadsOutstanding: Int = 64,
    maxWritesOutstanding: Int = 64,
    tagBits: Int = 6,
    ramPorts: SphereRamPorts = SphereRamPorts.Replicated,
    denseByDefault: Boolean = false,
    records: Option[RecordLayout] = None,
    world: Option[WorldConfig] = None,
    scpuImpl: ScpuImpl = ScpuImpl.Rtl,
    device: Device = Device.stratixVA7) {
  require(name.nonEmpty && name.forall(c => c.isLetterOrDigit || c == '-' || c == '_'),
    s"AfuConfig name '$name': must be non-empty letters, digits, '-' or '_'")
  require(scpus >= 1 && scpus <= 64, s"AfuConfig $name: scpus must be 1..64, got $scpus")
  require(tagBits >= 1 && tagBits <= 16, s"AfuConfig $name: tagBits must be 1..16, got $tagBits")
  require(maxReadsOutstanding >= 2 && maxReadsOutstanding <= (1 << tagBits),
    s"AfuConfig $name: maxReadsOutstanding must be 2..${1 << tagBits} (2^tagBits), got $maxReadsOutstanding")
  require(maxWritesOutstanding >= 2 && maxWritesOutstanding <= (1 << tagBits),
    s"AfuConfig $name: maxWritesOutstanding must be 2..${1 << tagBits} (2^tagBits), got $maxWritesOutstanding")
  require(scpu.tagBits >= 24, s"AfuConfig $name: the SCPU's tagBits must be >= 24 to carry a pair index, got ${scpu.tagBits}")
  require(maxSpheres >= 64 && maxSpheres <= 65536 && Integer.bitCount(maxSpheres) == 1,
    s"AfuConfig $name: maxSpheres must be a power of two in 64..65536 (pair indices are 16-bit), got $maxSpheres")

  for (why <- Some(scpuImpl).filter(_ == ScpuImpl.Model).flatMap(_ => ScpuImpl.modelRefusal(scpu)))
    require(false, s"AfuConfig $name: SCPU ${scpu.name} cannot be simulated by the C++ model: $why")
  for (r <- records; why <- r.refusal(scpu))
    require(false, s"AfuConfig $name: record layout ${r.name} is not offered for SCPU ${scpu.name}: $why")
  for (_ <- world) {
    require(!scpu.converts, s"AfuConfig $name: world mode reads the sphere table in the compute format, " +
      s"but SCPU ${scpu.name} converts its ${scpu.linkFormat.name} link values (or flushes subnormals)")
    require(maxSpheres <= (1 << RecordTag.WORLD_INDEX_BITS),
      s"AfuConfig $name: world mode holds at most ${1 << RecordTag.WORLD_INDEX_BITS} spheres (a record's pair field names i and j), got $maxSpheres")
    require(records.forall(!_.masked), s"AfuConfig $name: world mode needs an indexed record layout, not ${records.get.name}")
  }
  /** The broad phase's parameters where world mode is built. */
  def broadPhase: Option[collide.world.BroadPhaseParams] = world.map(_.broadPhase)
  /** A run queue (world mode only: WorldConfig.runQueue). */
  def runQueue: Boolean = world.exists(_.runQueue)
  /** The pair kinds this AFU has units for (docs/pair-kinds.md; the manifest's afu.pairKinds):
    * its SCPUs'. The other kinds' units (collide.pairs) are not built into an AFU yet. */
  def pairKinds: Seq[String] = Seq("sphere-sphere")
  /** The record layout in effect (bestLayout unless asked for). */
  val recordLayout: RecordLayout = records.getOrElse(AfuConfig.bestLayout(scpu, world.isDefined))

  val linkWidth: Int = scpu.linkWidth
  val layout: BufferLayout = BufferLayout(linkWidth, recordLayout)
  for (SphereRamPorts.Banked(Some(b)) <- Some(ramPorts); why <- SphereRamPorts.bankRefusal(b, layout.spheresPerLine, maxSpheres))
    require(false, s"AfuConfig $name: $why")
  /** Whether this is exactly the named preset. */
  def isPreset: Boolean = AfuConfig.presets.get(name).contains(this)
  /** A name from every parameter, for configurations that are not a preset. */
  def derivedName: String =
    s"n${scpus}_${scpu.id}_s${maxSpheres}_r${maxReadsOutstanding}_w${maxWritesOutstanding}_t${tagBits}_${ramPorts.name}" + (if (runQueue) "_q" else "") +
      (if (recordLayout != AfuConfig.bestLayout(scpu, world.isDefined)) s"_${recordLayout.name}" else "") +
      (if (denseByDefault) "_dense" else "") + world.map(_.idSuffix).getOrElse("") +
      (if (scpuImpl == ScpuImpl.Model) "_model" else "")
  /** Output folder and module-name suffix: the preset's name, else the derived name. */
  def id: String = (if (isPreset) name else derivedName).replace('-', '_')

  lazy val puc: PucParams = PucParams(
    scpus = scpus, linkWidth = linkWidth, scpuTagBits = scpu.tagBits, scpuLatency = scpu.latency,
    maxSpheres = maxSpheres, maxReads = maxReadsOutstanding, maxWrites = maxWritesOutstanding,
    tagBits = tagBits, ramPorts = ramPorts, denseByDefault = denseByDefault, records = recordLayout,
    world = world.map(w => PucWorld(w.broadPhase, scpu.params, w.lineQueue, w.startAhead)), tables = if (runQueue) 2 else 1, name = "_" + id)

  /** Pairs per cycle the dispatcher can reach (a group never spans two pair lines). */
  def peakPairsPerCycle: Double = {
    val ppl = layout.pairsPerLine
    if (scpus >= ppl) ppl.toDouble else ppl.toDouble / ((ppl + scpus - 1) / scpus)
  }
  /** Cycles from a pair's group dispatch to its result at the collector (no stalls):
    * sphere RAM read (1) + SCPU input queue (1) + SCPU latency. */
  def pairLatency: Int = 2 + scpu.latency
  def describe: String =
    s"$id: $scpus x SCPU ${scpu.describe}; maxSpheres $maxSpheres, reads $maxReadsOutstanding, writes $maxWritesOutstanding, " +
      s"tag $tagBits bits, sphere RAM ${ramPorts.name} ${puc.ramBits} bits, link ${scpu.linkFormat.name}, ${recordLayout.name} records " +
      s"(${layout.recordBytes} B, ${layout.recordsPerLine} a line), ${if (denseByDefault) "dense" else "compact"} by default" +
      broadPhase.map(bp => s", world mode built (${bp.lanes} candidate lane${if (bp.lanes > 1) "s" else ""}, ${bp.sortPorts} sort port${if (bp.sortPorts > 1) "s" else ""}, broad phase RAM ${bp.ramBits(maxSpheres)} bits, ${puc.broadPhaseM20k} M20K blocks by estimate; the sphere RAM's ${puc.ramM20k})").getOrElse("") +
      (if (runQueue) ", a run queue (two sphere tables)" + (if (world.exists(_.startAhead)) ", queued broad phases started ahead" else "") else "") +
      (if (scpuImpl == ScpuImpl.Model) ", SCPUs simulated by the C++ model (not synthesizable)" else "")
}

object AfuConfig {
  /** The layout that moves the fewest lines: derived values where the SCPU's arithmetic lets
    * the host rebuild contacts exactly, else full; masked when that puts more records in a
    * line than the indexed form (16- and 32-bit fields; at 64 bits both hold the same and the
    * headers would be extra). bench/results/masked measures it: fp32 derived-masked writes
    * 567 lines for the diamond at hMax 10 where derived writes 720. World mode takes the
    * indexed one: its records must name the spheres, which no mask header can. */
  def bestLayout(scpu: ScpuConfig, world: Boolean = false): RecordLayout = {
    val (indexed, masked) =
      if (RecordLayout.Derived.refusal(scpu).isEmpty) (RecordLayout.Derived, RecordLayout.DerivedMasked)
      else (RecordLayout.Full, RecordLayout.FullMasked)
    if (!world && BufferLayout(scpu.linkWidth, masked).recordsPerLine > BufferLayout(scpu.linkWidth, indexed).recordsPerLine) masked
    else indexed
  }

  val default: AfuConfig = AfuConfig()
  /** The paper's design point in our terms: 16 units, binary32, whole contacts on the link. */
  val paper: AfuConfig   = default.copy(name = "paper", records = Some(RecordLayout.Full))
  val small: AfuConfig   = default.copy(name = "small", scpus = 1, maxSpheres = 256)
  val fp16: AfuConfig    = default.copy(name = "fp16", scpu = ScpuConfig.fp16)
  val fp16Full: AfuConfig = fp16.copy(name = "fp16-full", records = Some(RecordLayout.Full))
  val fp16x4: AfuConfig  = default.copy(name = "fp16x4", scpus = 4, scpu = ScpuConfig.fp16)
  val fp64: AfuConfig    = default.copy(name = "fp64", scpu = ScpuConfig.fp64)
  val fp64Full: AfuConfig = fp64.copy(name = "fp64-full", records = Some(RecordLayout.Full))
  val fp32Nr: AfuConfig  = default.copy(name = "fp32-nr", scpu = ScpuConfig.fp32Nr)
  val big: AfuConfig     = default.copy(name = "big", maxSpheres = 4096)
  /** World mode: 16 fp32 SCPUs fed by the on-chip broad phase's 16 candidate lanes (claiming
    * their work as they need it, queueing eight spheres' hits, loading a chunk while the last
    * one's hits leave, looking up six visits ahead, pairing a coarse chunk's members as its
    * scan loads them), its sort's passes eight spheres
    * a cycle (four sorts of two ports), 32 counters a word, box buckets, up to 4096 spheres
    * a run, and a run queue: a world cut into several runs loads each run's table while the
    * run before it computes (bench/results/world-lanes, bench/results/world-afu). Built for the
    * Stratix 10 GX 2800: the area proxy puts it at 125 % of an Arria 10 GX 1150's ALMs by LUT
    * shape (docs/timing.md); `world-fit` fits the paper's part. */
  val world: AfuConfig   = big.copy(name = "world",
    world = Some(WorldConfig(collide.world.BroadPhaseParams.default.copy(lanes = 16, sortPorts = 8, wordLog2 = 5, chunk = 32,
      cellSteps = 2, coarseChunks = true, claims = true, hitQueue = 8, boxBuckets = true, drainBehind = true, lookAhead = 6, scanPairs = true),
      runQueue = true)),
    device = Device.stratix10GX2800)

  /** World mode at twice the lanes: the `world` preset with 32 candidate lanes and its sort's
    * passes 16 spheres a cycle, 256 candidate lines queued for the dispatcher, the sort's counters
    * cleared behind its scatter and a queued run's broad phase started ahead. The configuration
    * of the ideal-link study (docs/afu.md, "Starting ahead"); about twice the `world` preset's
    * broad-phase logic and three times its sort RAM, so a study of what the target costs, not a
    * design fitted to one FPGA: on the Arria 10 GX 1150 it is refused without --allow-overfit. */
  val world32: AfuConfig = world.copy(name = "world32",
    world = world.world.map(w => w.copy(broadPhase = w.broadPhase.copy(lanes = 32, sortPorts = 16, clearBehind = true),
      lineQueue = 256, startAhead = true)), device = Device.arria10GX1150)

  /** World mode on the paper's part: the `world` preset cut to fit the Stratix V GX A7
    * (5SGXEA7) of HARP v1, whose 234,720 ALMs hold neither the `world` preset's 16-lane broad
    * phase nor its 16 SCPUs at the depth that reaches 200 MHz. Half the lanes (the broad phase's
    * logic is mostly per lane) and four SCPUs (four pairs a cycle is more than eight lanes find:
    * bench/results/world-fit measures both, and the area proxy's ALMs against the part). */
  val worldFit: AfuConfig = world.copy(name = "world-fit", scpus = 4,
    world = world.world.map(w => w.copy(broadPhase = w.broadPhase.copy(lanes = 8))), device = Device.stratixVA7)

  /** The default AFU for fast co-simulation: its PUC in RTL, its SCPUs the C++ model behind
    * their pipelines (same cycles, same records; docs/afu.md, "A faster co-simulation"). */
  val cosim: AfuConfig = default.copy(name = "cosim", scpuImpl = ScpuImpl.Model)

  val all: Seq[AfuConfig] = Seq(default, cosim, paper, small, fp16, fp16Full, fp16x4, fp64, fp64Full, fp32Nr, big, world, worldFit, world32)
  val presets: Map[String, AfuConfig] = all.map(c => c.name -> c).toMap
}
