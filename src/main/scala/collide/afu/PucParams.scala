package collide.afu

/** How the on-chip sphere table gives each SCPU its two sphere reads a cycle. */
sealed trait SphereRamPorts { def name: String }
object SphereRamPorts {
  /** One copy of the table per SCPU, each with one write port (loading) and two read ports
    * (spheres i and j). Loading and computing never touch the table at the same time, so a
    * true-dual-port block RAM (e.g. Stratix V M20K) implements each copy. */
  case object Replicated extends SphereRamPorts { val name = "rep" }
  /** One copy of the table cut into `banks` RAMs one sphere wide, sphere s in bank s mod banks,
    * each with two read ports (again a true-dual-port block RAM). Reads of one sphere share a
    * port; a dispatch group is cut where a bank would see a third sphere in a cycle, so
    * conflicts cost time, never a pair.
    * None: 2 x min(scpus, 16) banks (one per read of a full group), at least a line's spheres. */
  final case class Banked(banks: Option[Int] = None) extends SphereRamPorts {
    require(banks.forall(validBanks), s"banks must be a power of two in 1..256, got ${banks.get}")
    val name: String = banks.fold("bank")(b => s"bank$b")
  }

  /** Bank counts a table can be cut into. */
  def validBanks(n: Int): Boolean = n >= 1 && n <= 256 && Integer.bitCount(n) == 1
  /** Why `banks` banks cannot hold a table of `maxSpheres` spheres written `spheresPerLine` a line. */
  def bankRefusal(banks: Int, spheresPerLine: Int, maxSpheres: Int): Option[String] =
    if (banks >= spheresPerLine && banks <= maxSpheres / 2) None
    else Some(s"banked sphere RAM: $banks banks; at least the $spheresPerLine spheres of a line (a line write meets each bank " +
      s"once) and at most maxSpheres / 2 (${maxSpheres / 2})")

  def parse(s: String): Either[String, SphereRamPorts] = s.trim.toLowerCase match {
    case "rep" | "replicated" => Right(Replicated)
    case "bank" | "banked" => Right(Banked())
    case b if b.startsWith("banked:") || b.startsWith("bank:") =>
      val v = b.dropWhile(_ != ':').drop(1)
      v.toIntOption.filter(validBanks)
        .toRight(s"sphere RAM ports '$s': banks must be a power of two in 1..256, got '$v'").map(n => Banked(Some(n)))
    case other => Left(s"sphere RAM ports '$other': expected 'replicated', 'banked' or 'banked:B' (B banks, a power of two)")
  }
}

/** World mode's part of the PUC: the broad phase's parameters, the compute format it reads the
  * sphere table in (world mode needs the link format to be the compute format), the pair lines
  * queued for the dispatcher, and whether a queued world run's broad phase starts ahead
  * (WorldConfig.lineQueue, WorldConfig.startAhead). */
final case class PucWorld(bp: collide.world.BroadPhaseParams, fp: collide.fp.FpParams, lineQueue: Int = 2,
                          startAhead: Boolean = false)

/** What the PUC (everything of the AFU but the SCPUs) needs to know. Derived from AfuConfig;
  * kept apart so the memory side does not depend on the floating-point configuration.
  *
  * @param scpus        SCPUs to feed (1..64)
  * @param linkWidth    bits of one link field: 16 (binary16 or bfloat16), 32 (binary32), 64 (binary64)
  * @param scpuTagBits  the SCPU's tag width (carries the pair index: at least 24)
  * @param scpuLatency  the SCPU's pipeline latency (sizes the in-flight bookkeeping)
  * @param maxSpheres   on-chip sphere table entries
  * @param maxReads     read requests in flight at most
  * @param maxWrites    write requests in flight at most
  * @param tagBits      link tag width
  * @param ramPorts     sphere table read-port strategy
  * @param denseByDefault reset value of MODE bit 0
  * @param records      what a contact record carries (RecordLayout)
  * @param world        the broad phase, when world mode is built (MODE bit 1)
  * @param tables       sphere tables on chip: 1, or 2 for the run queue (a world run started
  *                     while one runs waits, its table loading into the other table)
  * @param name         suffix of every module name, so two configurations never collide
  */
final case class PucParams(
    scpus: Int,
    linkWidth: Int,
    scpuTagBits: Int,
    scpuLatency: Int,
    maxSpheres: Int,
    maxReads: Int,
    maxWrites: Int,
    tagBits: Int,
    ramPorts: SphereRamPorts = SphereRamPorts.Replicated,
    denseByDefault: Boolean = false,
    records: RecordLayout = RecordLayout.Full,
    world: Option[PucWorld] = None,
    tables: Int = 1,
    name: String = "") {
  require(scpus >= 1 && scpus <= 64, s"scpus must be 1..64, got $scpus")
  require(linkWidth == 16 || linkWidth == 32 || linkWidth == 64, s"linkWidth must be 16, 32 or 64, got $linkWidth")
  require(scpuTagBits >= 24, s"scpuTagBits must be >= 24 (it carries the pair index), got $scpuTagBits")
  require(scpuLatency >= 0, s"scpuLatency must be >= 0, got $scpuLatency")
  require(maxReads >= 2 && maxReads <= (1 << tagBits), s"maxReads must be 2..2^tagBits (${1 << tagBits}), got $maxReads")
  require(maxWrites >= 2 && maxWrites <= (1 << tagBits), s"maxWrites must be 2..2^tagBits (${1 << tagBits}), got $maxWrites")
  require(tables == 1 || tables == 2, s"tables must be 1 or 2, got $tables")
  require(tables == 1 || world.isDefined, "a run queue (two sphere tables) needs world mode: it loads a queued world run's table")
  val layout: BufferLayout = BufferLayout(linkWidth, records)
  require(world.isEmpty || maxSpheres <= (1 << RecordTag.WORLD_INDEX_BITS),
    s"world mode: maxSpheres must be at most ${1 << RecordTag.WORLD_INDEX_BITS} (a record's pair field holds i and j), got $maxSpheres")
  require(world.isEmpty || !layout.masked, s"world mode needs an indexed record layout (a record names its spheres), got ${records.name}")
  require(world.forall(_.fp.width == linkWidth), "world mode: the broad phase reads the table in the link format, which must be the compute format")
  require(maxSpheres >= 64 && maxSpheres % layout.spheresPerLine == 0 && maxSpheres <= 65536,
    s"maxSpheres must be a multiple of ${layout.spheresPerLine} (spheres a line) in 64..65536, got $maxSpheres")

  /** Pairs dispatched per cycle at most: a group never spans two pair lines. */
  val lanes: Int = math.min(scpus, layout.pairsPerLine)
  /** Pair lines buffered on chip: one slot reserved for every pair read in flight. */
  val pairBufferLines: Int = maxReads
  /** Entries of each SCPU's input queue (covers the sphere RAM's read latency at full rate). */
  val scpuQueueDepth: Int = 3
  /** Dispatched groups whose results are not yet collected, at most. */
  val groupsInFlight: Int = {
    val perScpu = scpuLatency + scpuQueueDepth + 2
    val g = perScpu * ((scpus + lanes - 1) / lanes) + 4
    1 << chisel3.util.log2Ceil(g)
  }
  /** Contact lines buffered between the packer and the write channel. */
  val writeQueueLines: Int = 8
  val sphereLineBits: Int = chisel3.util.log2Ceil(maxSpheres / layout.spheresPerLine)
  val pairLineBits: Int = layout.pairIndexBits - chisel3.util.log2Ceil(layout.pairsPerLine)
  /** Copies the broad phase reads in world mode (it reads the table while the SCPUs compute
    * the candidates it found earlier): one per two lanes. */
  val worldCopies: Int = world.map(_.bp.sphereCopies).getOrElse(0)
  /** One copy per SCPU (or one banked copy), and the broad phase's. */
  val ramCopies: Int = ramPorts match {
    case SphereRamPorts.Replicated => scpus + worldCopies
    case _: SphereRamPorts.Banked  => 1 + worldCopies
  }
  /** Banks of the SCPUs' copy (1 when replicated: each copy is one line-wide RAM). */
  val banks: Int = ramPorts match {
    case SphereRamPorts.Replicated => 1
    case SphereRamPorts.Banked(b) => b.getOrElse(math.max(1 << chisel3.util.log2Ceil(2 * lanes), layout.spheresPerLine))
  }
  /** Whether the SCPUs read one banked copy (PairDispatcher names each read's port). */
  val banked: Boolean = ramPorts != SphereRamPorts.Replicated
  for (why <- if (banked) SphereRamPorts.bankRefusal(banks, layout.spheresPerLine, maxSpheres) else None) require(false, why)
  /** Sphere table bits on chip, all copies (each copy holds `tables` tables). */
  val ramBitsPerCopy: Long = maxSpheres.toLong * 4 * linkWidth * tables
  val ramBits: Long = ramBitsPerCopy * ramCopies
  /** Stratix V M20K blocks of the sphere table, all copies (M20k: an estimate). The SCPUs'
    * copies need two read ports; the broad phase's one per lane, two lanes a copy. */
  val ramM20k: Long = {
    val lines = maxSpheres / layout.spheresPerLine
    val scpuCopies = ramPorts match {
      case SphereRamPorts.Replicated => scpus * M20k.blocks(lines, Link.lineBits, twoPorts = true)
      case _: SphereRamPorts.Banked  => banks * M20k.blocks(maxSpheres / banks, 4 * linkWidth, twoPorts = true)
    }
    val worldLanes = world.map(_.bp.lanes).getOrElse(0)
    // A run queue's second table is a RAM of its own beside each (SphereRam: never three ports).
    tables * (scpuCopies + (worldLanes / 2) * M20k.blocks(lines, Link.lineBits, twoPorts = true) +
      (worldLanes % 2) * M20k.blocks(lines, Link.lineBits, twoPorts = false))
  }
  /** Stratix V M20K blocks of the broad phase's RAMs (BroadPhaseParams.rams), each RAM in its
    * cheapest mode (M20k: an estimate); 0 without world mode. */
  val broadPhaseM20k: Long = world.map(_.bp.rams(maxSpheres).map(r => r.count * M20k.blocks(r.words, r.width, r.twoWrites)).sum).getOrElse(0L)
  val pairBufferBits: Long = pairBufferLines.toLong * (Link.lineBits + pairLineBits)
}
