package collide.afu

/** Every number of docs/afu-interface.md that both sides must agree on, in one place: the
  * RTL, the manifest and the C++ header all read them from here.
  */
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
  val all: Seq[(String, Int)] = Seq(
    "CTRL" -> CTRL, "SPHERE_BASE" -> SPHERE_BASE, "NUM_SPHERES" -> NUM_SPHERES,
    "PAIR_BASE" -> PAIR_BASE, "NUM_PAIRS" -> NUM_PAIRS, "CONTACT_BASE" -> CONTACT_BASE,
    "CONTACT_CAPACITY" -> CONTACT_CAPACITY, "STATUS_ADDR" -> STATUS_ADDR, "MODE" -> MODE)
  /** CTRL value that starts a run; MODE bit 0 selects dense records. */
  val CTRL_START = 1
  val MODE_DENSE = 1
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
  val CYCLES_TOTAL    = 32
  val CYCLES_LOAD     = 36
  val CYCLES_COMPUTE  = 40
  val CYCLES_WAIT_RD  = 44
  val CYCLES_WAIT_WR  = 48
  val all: Seq[(String, Int)] = Seq(
    "DONE" -> DONE, "ERROR_FLAGS" -> ERROR_FLAGS, "PAIRS_PROCESSED" -> PAIRS_PROCESSED,
    "CONTACTS_FOUND" -> CONTACTS_FOUND, "RECORDS_WRITTEN" -> RECORDS_WRITTEN,
    "NONFINITE_PAIRS" -> NONFINITE_PAIRS, "FIRST_BAD_PAIR" -> FIRST_BAD_PAIR,
    "CYCLES_TOTAL" -> CYCLES_TOTAL, "CYCLES_LOAD" -> CYCLES_LOAD, "CYCLES_COMPUTE" -> CYCLES_COMPUTE,
    "CYCLES_WAIT_RD" -> CYCLES_WAIT_RD, "CYCLES_WAIT_WR" -> CYCLES_WAIT_WR)
  val NO_BAD_PAIR = 0xFFFFFFFFL
}

/** Error flag bits of the status line. */
object ErrorFlags {
  val INDEX_RANGE    = 1 << 0
  val TOO_MANY_SPHERES = 1 << 1
  val CAPACITY       = 1 << 2
  val NONFINITE      = 1 << 3
  val BAD_CONFIG     = 1 << 4
  val width          = 5
  val all: Seq[(String, Int)] = Seq("INDEX_RANGE" -> INDEX_RANGE, "TOO_MANY_SPHERES" -> TOO_MANY_SPHERES,
    "CAPACITY" -> CAPACITY, "NONFINITE" -> NONFINITE, "BAD_CONFIG" -> BAD_CONFIG)
}

/** Record flag bits (bits 24..31 of a binary32 record's last word; the flags word in binary64). */
object RecordFlags {
  val HIT        = 1 << 0
  val KIND_SHIFT = 1       // bits 1..2: collide.scpu.ContactKind
  val NONFINITE  = 1 << 3
  val ARITH      = 1 << 4  // the SCPU's arithmetic raised overflow or invalid
  val all: Seq[(String, Int)] = Seq("HIT" -> HIT, "KIND_SHIFT" -> KIND_SHIFT, "NONFINITE" -> NONFINITE, "ARITH" -> ARITH)
}

/** Buffer layout for one link width (32: IEEE binary32, 64: binary64). */
final case class BufferLayout(linkWidth: Int) {
  require(linkWidth == 32 || linkWidth == 64, s"link width must be 32 or 64, got $linkWidth")
  val sphereBytes: Int    = 4 * linkWidth / 8
  val spheresPerLine: Int = Link.lineBytes / sphereBytes
  val pairBytes: Int      = 4
  val pairsPerLine: Int   = Link.lineBytes / pairBytes
  val recordBytes: Int    = if (linkWidth == 32) 32 else 64
  val recordsPerLine: Int = Link.lineBytes / recordBytes
  /** Bit offset of the pair index / flags in a record. */
  val pairIndexBit: Int   = if (linkWidth == 32) 7 * 32 else 7 * 64
  val flagsBit: Int       = if (linkWidth == 32) 7 * 32 + 24 else 7 * 64 + 32
  val pairIndexBits: Int  = 24
  val maxPairs: Long      = 1L << pairIndexBits
  def sphereLines(n: Long): Long  = (n + spheresPerLine - 1) / spheresPerLine
  def pairLines(n: Long): Long    = (n + pairsPerLine - 1) / pairsPerLine
  def contactLines(n: Long): Long = (n + recordsPerLine - 1) / recordsPerLine
}
