package collide.fp

/** A binary floating-point format: `expBits` exponent bits and `sigBits` significand bits
  * *including* the hidden bit (so IEEE binary32 is (8, 24)). Encoding is IEEE-754 style:
  * sign | biased exponent | fraction, all-ones exponent for infinities and NaNs.
  */
final case class FloatFormat(expBits: Int, sigBits: Int) {
  require(expBits >= 3 && expBits <= 15,
    s"format ($expBits,$sigBits): exponent bits must be 3..15, got $expBits")
  require(sigBits >= 3 && sigBits <= 64,
    s"format ($expBits,$sigBits): significand bits (with the hidden bit) must be 3..64, got $sigBits")

  val fracBits: Int = sigBits - 1
  val width: Int    = expBits + sigBits
  val bias: Int     = (1 << (expBits - 1)) - 1
  /** Unbiased exponent of the largest and smallest normal numbers. */
  val maxExp: Int = bias
  val minExp: Int = 1 - bias
  /** Exponent of the smallest subnormal's value: 2^(minExp - fracBits). */
  val minSubExp: Int = minExp - fracBits

  /** Signed width that holds the unbiased exponent of any finite value once subnormals are
    * normalized (minSubExp .. maxExp + 1), with one bit to spare: RawFloat.sExp's width. */
  val rawExpWidth: Int = {
    val maxAbs = math.max(maxExp + 2, -minSubExp + 1)
    32 - Integer.numberOfLeadingZeros(maxAbs) + 2
  }

  /** Preset name if this is one, else e<E>m<M>. */
  def name: String = FloatFormat.presetName(this).getOrElse(s"e${expBits}m$sigBits")

  /** Whether IEEE binary32 holds every value of this format. */
  def fitsBinary32: Boolean = expBits <= 8 && sigBits <= 24
  /** Whether every value of this format is also a value of `wider` (no rounding, no overflow). */
  def fitsIn(wider: FloatFormat): Boolean = expBits <= wider.expBits && sigBits <= wider.sigBits
  /** The default link format for this compute format (docs/afu-interface.md, "Link format"):
    * the 16-bit formats travel as themselves, so a narrow SCPU moves half the bytes; any other
    * format the narrowest of binary32 and binary64 that holds it. */
  def linkFormat: FloatFormat =
    if (FloatFormat.linkFormats16.contains(this)) this
    else if (fitsBinary32) FloatFormat.fp32 else FloatFormat.fp64

  // Bit patterns, as BigInt so fp64 and wider significands need no special casing.
  def expMask: BigInt   = (BigInt(1) << expBits) - 1
  def fracMask: BigInt  = (BigInt(1) << fracBits) - 1
  def signBit: BigInt   = BigInt(1) << (width - 1)
  def infinity(negative: Boolean): BigInt = (if (negative) signBit else BigInt(0)) | (expMask << fracBits)
  /** The one canonical NaN every operator returns: positive, quiet bit set, rest zero. */
  def canonicalNaN: BigInt = (expMask << fracBits) | (BigInt(1) << (fracBits - 1))
  def zero(negative: Boolean): BigInt = if (negative) signBit else BigInt(0)
  def maxFinite(negative: Boolean): BigInt =
    (if (negative) signBit else BigInt(0)) | ((expMask - 1) << fracBits) | fracMask
}

object FloatFormat {
  val bf16 = FloatFormat(8, 8)
  val fp16 = FloatFormat(5, 11)
  val fp24 = FloatFormat(8, 16)
  val fp32 = FloatFormat(8, 24)
  val fp64 = FloatFormat(11, 53)
  /** 16-bit formats the link can carry as they are (the host decodes both). */
  val linkFormats16: Seq[FloatFormat] = Seq(fp16, bf16)
  /** Every format a link field may have: one a host can encode and decode exactly. */
  val linkFormats: Seq[FloatFormat] = Seq(fp16, bf16, fp32, fp64)

  val presets: Seq[(String, FloatFormat)] =
    Seq("bf16" -> bf16, "fp16" -> fp16, "fp24" -> fp24, "fp32" -> fp32, "fp64" -> fp64)

  def presetName(f: FloatFormat): Option[String] = presets.find(_._2 == f).map(_._1)

  /** Parses a preset name ("fp32"), "e8m24" or "8,24". Errors name the input and the problem. */
  def parse(s: String): Either[String, FloatFormat] = {
    val t = s.trim.toLowerCase
    val Em = """e(\d+)m(\d+)""".r
    val Pair = """\(?\s*(\d+)\s*,\s*(\d+)\s*\)?""".r
    def build(e: String, m: String): Either[String, FloatFormat] =
      try Right(FloatFormat(e.toInt, m.toInt))
      catch { case ex: IllegalArgumentException => Left(s"format '$s': ${ex.getMessage.stripPrefix("requirement failed: ")}") }
    presets.toMap.get(t) match {
      case Some(f) => Right(f)
      case None => t match {
        case Em(e, m)   => build(e, m)
        case Pair(e, m) => build(e, m)
        case _ => Left(s"format '$s': not a preset (${presets.map(_._1).mkString(", ")}) nor eEmM nor 'E,M'")
      }
    }
  }
}
