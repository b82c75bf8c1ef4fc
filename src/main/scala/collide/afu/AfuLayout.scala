package collide.afu

import collide.fp.{FloatFormat, RoundingMode}
import collide.scpu.{DistanceMethod, ScpuConfig}

/** Every number of docs/afu-interface.md that both sides must agree on, in one place: the
  * RTL reads them from here, and AfuContract writes the configuration-independent C++ and
  * SystemVerilog headers every host-side consumer includes. Each entry carries the sentence
  * the headers print beside it.
  */
final case class ContractEntry(name: String, value: Long, doc: String)

object Csr {
  val CTRL             = 0
  val SPHERE_BASE      = 1
  val NUM_SPHERES      = 2
  val PAIR_BASE        = 3
  val NUM_PAIRS        = 4
  val CONTACT_BASE     = 5
  val CONTACT_CAPACITY = 6
  val STATUS_ADDR      = 7
  val MODE             = 8
  val count            = 9
  val entries: Seq[ContractEntry] = Seq(
    ContractEntry("CTRL", CTRL, "write CTRL_START to start a run (during a run: queued where afu.runQueue, else ignored)"),
    ContractEntry("SPHERE_BASE", SPHERE_BASE, "line address of the sphere table"),
    ContractEntry("NUM_SPHERES", NUM_SPHERES, "spheres in the table"),
    ContractEntry("PAIR_BASE", PAIR_BASE, "line address of the pair list"),
    ContractEntry("NUM_PAIRS", NUM_PAIRS, "pairs in the list (< 2^PAIR_INDEX_BITS)"),
    ContractEntry("CONTACT_BASE", CONTACT_BASE, "line address of the contact buffer"),
    ContractEntry("CONTACT_CAPACITY", CONTACT_CAPACITY, "contact records the buffer holds"),
    ContractEntry("STATUS_ADDR", STATUS_ADDR, "line address of the status line"),
    ContractEntry("MODE", MODE, "bit 0: dense records; bit 1: world mode (AFUs built with a broad phase)"))
  val all: Seq[(String, Int)] = entries.map(e => e.name -> e.value.toInt)
  /** CTRL value that starts a run; MODE bit 0 selects dense records, bit 1 world mode (the
    * AFU's broad phase makes the pairs from the sphere table; PAIR_BASE and NUM_PAIRS unused). */
  val CTRL_START = 1
  val MODE_DENSE = 1
  val MODE_WORLD = 2
}

/** Byte offsets of the status line's u32 fields. */
object StatusLine {
  val DONE            = 0
  val ERROR_FLAGS     = 4
  val PAIRS_PROCESSED = 8
  val CONTACTS_FOUND  = 12
  val RECORDS_WRITTEN = 16
  val NONFINITE_PAIRS = 20
  val FIRST_BAD_PAIR  = 24
  val FLAGGED_MISSES  = 28
  val CYCLES_TOTAL    = 32
  val CYCLES_LOAD     = 36
  val CYCLES_COMPUTE  = 40
  val CYCLES_WAIT_RD  = 44
  val CYCLES_WAIT_WR  = 48
  val CYCLES_BROAD    = 52
  val WORLD_CELL_LEVEL = 56
  val WORLD_LARGE     = 60
  val entries: Seq[ContractEntry] = Seq(
    ContractEntry("DONE", DONE, "1 when the run is over"),
    ContractEntry("ERROR_FLAGS", ERROR_FLAGS, "ERR_* bits"),
    ContractEntry("PAIRS_PROCESSED", PAIRS_PROCESSED, "every pair read, bad ones included"),
    ContractEntry("CONTACTS_FOUND", CONTACTS_FOUND, "hits (may exceed the records written)"),
    ContractEntry("RECORDS_WRITTEN", RECORDS_WRITTEN, "contact records written"),
    ContractEntry("NONFINITE_PAIRS", NONFINITE_PAIRS, "pairs with a NaN or infinite input"),
    ContractEntry("FIRST_BAD_PAIR", FIRST_BAD_PAIR, "lowest pair with an index out of range, or NO_BAD_PAIR"),
    ContractEntry("FLAGGED_MISSES", FLAGGED_MISSES, "misses with NONFINITE or ARITH set; pair mode writes a record for each, compact too"),
    ContractEntry("CYCLES_TOTAL", CYCLES_TOTAL, "cycles from start to the status write"),
    ContractEntry("CYCLES_LOAD", CYCLES_LOAD, "cycles loading the sphere table"),
    ContractEntry("CYCLES_COMPUTE", CYCLES_COMPUTE, "cycles in which a group of pairs was dispatched"),
    ContractEntry("CYCLES_WAIT_RD", CYCLES_WAIT_RD, "cycles waiting on read responses"),
    ContractEntry("CYCLES_WAIT_WR", CYCLES_WAIT_WR, "cycles waiting on write responses or back-pressure"),
    ContractEntry("CYCLES_BROAD", CYCLES_BROAD, "world mode: cycles the broad phase ran (0 in pair mode)"),
    ContractEntry("WORLD_CELL_LEVEL", WORLD_CELL_LEVEL, "world mode: the grid's cell level L, a signed i32: cells of edge 2^(L/2) for even L, 1.5 * 2^((L-1)/2) for odd L"),
    ContractEntry("WORLD_LARGE", WORLD_LARGE, "world mode: spheres too large for the cell, paired with every sphere"))
  val all: Seq[(String, Int)] = entries.map(e => e.name -> e.value.toInt)
  /** The u32 fields in offset order (the decoders iterate these, never literal offsets). */
  val fields: Int = 16
  val NO_BAD_PAIR = 0xFFFFFFFFL
}

/** Error flag bits of the status line, each with the sentence a host prints for it. */
object ErrorFlags {
  val INDEX_RANGE      = 1 << 0
  val TOO_MANY_SPHERES = 1 << 1
  val CAPACITY         = 1 << 2
  val NONFINITE        = 1 << 3
  val BAD_CONFIG       = 1 << 4
  val WORLD_CHECK      = 1 << 5
  val entries: Seq[ContractEntry] = Seq(
    ContractEntry("INDEX_RANGE", INDEX_RANGE, "sphere index out of range"),
    ContractEntry("TOO_MANY_SPHERES", TOO_MANY_SPHERES, "NUM_SPHERES above the on-chip table"),
    ContractEntry("CAPACITY", CAPACITY, "contact buffer too small"),
    ContractEntry("NONFINITE", NONFINITE, "non-finite input seen"),
    ContractEntry("BAD_CONFIG", BAD_CONFIG, "bad configuration"),
    ContractEntry("WORLD_CHECK", WORLD_CHECK, "the broad phase's internal check failed (a bug: contacts may be missing)"))
  val width: Int = entries.size
  require(entries.map(_.value).zipWithIndex.forall { case (v, i) => v == (1L << i) }, "error flags must be bits 0..n-1")
  val all: Seq[(String, Int)] = entries.map(e => e.name -> e.value.toInt)
}

/** Record flag bits (the top byte of a record's tag word). Bit 5 is never written by the
  * AFU: a host sets it on a pair whose inputs did not fit the link format. */
object RecordFlags {
  val HIT        = 1 << 0
  val KIND_SHIFT = 1       // bits 1..2: collide.scpu.ContactKind
  val KIND_MASK  = 3
  val NONFINITE  = 1 << 3
  val ARITH      = 1 << 4  // the SCPU's arithmetic raised overflow or invalid
  val HOST_RANGE = 1 << 5  // host only: an input overflowed the link format, a radius rounded to 0, or a value outside the sane range (docs/host.md, "Bad pairs")
  val entries: Seq[ContractEntry] = Seq(
    ContractEntry("HIT", HIT, "the pair is a contact"),
    ContractEntry("KIND_SHIFT", KIND_SHIFT, "bits 1..2: KIND_*"),
    ContractEntry("KIND_MASK", KIND_MASK, "mask of the kind after the shift"),
    ContractEntry("NONFINITE", NONFINITE, "a NaN or infinity among the pair's inputs"),
    ContractEntry("ARITH", ARITH, "the arithmetic raised overflow or invalid"),
    ContractEntry("HOST_RANGE", HOST_RANGE, "set by the host: an input did not fit the link format or is outside the range every backend takes"))
  val all: Seq[(String, Int)] = entries.map(e => e.name -> e.value.toInt)
  /** The kinds (collide.scpu.ContactKind). */
  val kinds: Seq[ContractEntry] = Seq(
    ContractEntry("KIND_SEPARATED", 0, "no contact"), ContractEntry("KIND_CONTACT", 1, "0 < d <= r1 + r2"),
    ContractEntry("KIND_COINCIDENT", 2, "d <= 0: pos p1, normal (1,0,0), depth r1 + r2"),
    ContractEntry("KIND_INVALID", 3, "a sphere index out of range"))
}

/** The record tag word: a u32 after a record's value fields. */
object RecordTag {
  val PAIR_BITS   = 24 // bits 0..23: the pair index
  /** World mode: the pair field holds sphere i in bits 0..11 and j in bits 12..23 (i < j),
    * so world-mode AFUs hold at most 2^12 spheres. */
  val WORLD_INDEX_BITS = 12
  val FLAGS_SHIFT = 24 // bits 24..31: RecordFlags
  val BYTES       = 4
}

/** What a contact record carries (docs/afu-interface.md, "Contacts"): its value fields,
  * and how a record says which pair it is. Indexed layouts end each record with the tag
  * word (pair index and flags); masked layouts end it with the flags byte alone and, in
  * compact mode, put a MaskHeader (first pair, hit mask) before the hits of each group of
  * pairs the AFU computed together, so the pair index is not repeated in every record. */
sealed trait RecordLayout {
  def name: String
  /** Contract id (LAYOUT_* in the headers and `buffers.records.layout` in the manifest). */
  def code: Int
  /** The value fields in order, each one link word. */
  def fields: Seq[String]
  /** Pair indices by position (mask headers in compact mode), not in each record. */
  def masked: Boolean
  /** Why this layout cannot be offered for `cfg`, if it cannot. */
  def refusal(cfg: ScpuConfig): Option[String]
}
object RecordLayout {
  val fullFields: Seq[String]    = Seq("px", "py", "pz", "nx", "ny", "nz", "depth")
  val derivedFields: Seq[String] = Seq("d", "w")
  /** Position, normal and depth: the contact as a physics engine takes it. */
  case object Full extends RecordLayout {
    val name = "full"; val code = 0; val fields = fullFields; val masked = false
    def refusal(cfg: ScpuConfig): Option[String] = None
  }
  /** Only the two values that need a square root or a reciprocal: d and the normal's factor
    * w (n = u * w, u = p1 - p2, or the Robust method's scaled difference). The host rebuilds
    * u, n, k, pos and depth from its own sphere table with + and x in the compute format,
    * in the SCPU's order, so its contacts are bit for bit those of Full. That needs
    * operations the host reproduces exactly: RNE, subnormals kept, and either binary64
    * itself or a significand of at most 25 bits, so that one binary64 operation followed by
    * one rounding to the format equals the format's own operation (the 2p+2 rule). */
  case object Derived extends RecordLayout {
    val name = "derived"; val code = 1; val fields = derivedFields; val masked = false
    def refusal(cfg: ScpuConfig): Option[String] =
      if (cfg.rounding != RoundingMode.RNE) Some(s"the host rebuilds contacts in RNE only, the SCPU rounds ${cfg.rounding}")
      else if (!cfg.subnormals) Some("the host rebuilds contacts with subnormals kept, the SCPU flushes them")
      else if (cfg.format != FloatFormat.fp64 && cfg.format.sigBits > 25)
        Some(s"${cfg.format.name} has ${cfg.format.sigBits} significand bits: binary64 cannot emulate it exactly (2p+2 > 53) and it is not binary64")
      else None
  }
  /** Full's values, masked. */
  case object FullMasked extends RecordLayout {
    val name = "full-masked"; val code = 2; val fields = fullFields; val masked = true
    def refusal(cfg: ScpuConfig): Option[String] = None
  }
  /** Derived's values, masked: the fewest bytes a contact (offered where Derived is). */
  case object DerivedMasked extends RecordLayout {
    val name = "derived-masked"; val code = 3; val fields = derivedFields; val masked = true
    def refusal(cfg: ScpuConfig): Option[String] = Derived.refusal(cfg)
  }
  val all: Seq[RecordLayout] = Seq(Full, Derived, FullMasked, DerivedMasked)
  def parse(s: String): Either[String, RecordLayout] =
    all.find(_.name.equalsIgnoreCase(s.trim)).toRight(s"record layout '$s': expected one of ${all.map(_.name).mkString(", ")}")
}

/** The slot before a group's hits in a masked layout's compact buffer: the group's first
  * pair index and a bit per pair of the group (bit k: pair first + k hit), the rest zero.
  * A group is what the AFU computes in one go: up to min(SCPUs, 16) consecutive pairs of one
  * pair line. Only groups with a hit get a header, so the buffer holds headers + hits slots. */
object MaskHeader {
  val PAIR_SHIFT = 0
  val PAIR_BITS  = RecordTag.PAIR_BITS
  val MASK_SHIFT = 24
  val MASK_BITS  = 16
  val BITS       = MASK_SHIFT + MASK_BITS
  val entries: Seq[ContractEntry] = Seq(
    ContractEntry("PAIR_SHIFT", PAIR_SHIFT, "bits 0..23: the group's first pair index"),
    ContractEntry("PAIR_BITS", PAIR_BITS, "width of the first pair index"),
    ContractEntry("MASK_SHIFT", MASK_SHIFT, "bits 24..39: bit k set when pair first + k has a record (a hit or a flagged miss)"),
    ContractEntry("MASK_BITS", MASK_BITS, "width of the record mask (a group has at most 16 pairs)"),
    ContractEntry("BITS", BITS, "bits of a header (the rest of its slot is zero)"))
}

/** Buffer layout for one link format and record layout. Records (and, masked, headers) are
  * slots of `recordBytes`, packed whole with no padding, `recordsPerLine` a line from byte
  * 0; the rest of a line is zero. */
final case class BufferLayout(linkWidth: Int, records: RecordLayout = RecordLayout.Full) {
  require(linkWidth == 16 || linkWidth == 32 || linkWidth == 64, s"link width must be 16, 32 or 64, got $linkWidth")
  val sphereBytes: Int    = 4 * linkWidth / 8
  val spheresPerLine: Int = Link.lineBytes / sphereBytes
  val pairBytes: Int      = 4
  val pairsPerLine: Int   = Link.lineBytes / pairBytes
  val valueFields: Int    = records.fields.size
  val masked: Boolean     = records.masked
  /** Bits after the value fields: the tag word, or the flags byte alone when masked. */
  val tagBits: Int        = if (masked) 8 else RecordTag.BYTES * 8
  val recordBits: Int     = valueFields * linkWidth + tagBits
  val recordBytes: Int    = recordBits / 8
  val recordsPerLine: Int = Link.lineBytes / recordBytes
  require(!masked || recordBits >= MaskHeader.BITS, s"a ${records.name} slot of $recordBits bits cannot hold a mask header")
  /** Bit offset of the pair index (indexed layouts) and of the flags in a record. */
  val pairIndexBit: Option[Int] = if (masked) None else Some(valueFields * linkWidth)
  val flagsBit: Int       = valueFields * linkWidth + (if (masked) 0 else RecordTag.FLAGS_SHIFT)
  val pairIndexBits: Int  = RecordTag.PAIR_BITS
  val maxPairs: Long      = 1L << pairIndexBits
  def sphereLines(n: Long): Long  = (n + spheresPerLine - 1) / spheresPerLine
  def pairLines(n: Long): Long    = (n + pairsPerLine - 1) / pairsPerLine
  def contactLines(n: Long): Long = (n + recordsPerLine - 1) / recordsPerLine
  /** Dense mode: every pair line's records start a contact line (the ContactPacker). */
  val denseLinesPerPairLine: Int = (pairsPerLine + recordsPerLine - 1) / recordsPerLine
  def denseLine(k: Long): Long = (k / pairsPerLine) * denseLinesPerPairLine + (k % pairsPerLine) / recordsPerLine
  def denseSlot(k: Long): Int = ((k % pairsPerLine) % recordsPerLine).toInt
  def denseContactLines(n: Long): Long = if (n == 0) 0 else denseLine(n - 1) + 1
  /** Lines a buffer of `capacity` records takes in either mode. */
  def contactBufferLines(capacity: Long, dense: Boolean): Long = if (dense) denseContactLines(capacity) else contactLines(capacity)
  /** Compact slots `hits` contacts can take at most: one each, and masked a header for each
    * group with a hit (never more groups than hits). */
  def compactSlotsFor(hits: Long): Long = if (masked) 2 * hits else hits
}
