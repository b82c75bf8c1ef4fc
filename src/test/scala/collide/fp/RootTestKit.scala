package collide.fp

import chisel3._
import chiseltest._
import collide.fp.model.FpResult
import scala.util.Random

/** Shared test kit of the root-type operator specs (FpSqrtSpec, FpRecipSpec, FpRsqrtSpec):
  * independent oracles, operand patterns and a streaming RTL harness.
  */
object RootTestKit {

  // ---------------------------------------------------------------- exact oracle
  /** Correctly rounded sqrt / 1/a / 1/sqrt(a) with flags, from exact integer comparisons
    * against candidate results only: no roundPack, no shared decode, no digit recurrence.
    */
  object ExactOracle {
    /** sign(P * 2^k - Q * 2^j) for P, Q >= 0. */
    private def cmpScaled(pp: BigInt, k: Int, qq: BigInt, j: Int): Int =
      if (k >= j) ((pp << (k - j)) - qq).signum else (pp - (qq << (j - k))).signum

    def apply(op: RootOp, p: FpParams, a: BigInt, rm: RoundingMode): FpResult = {
      val f = p.format
      val sign  = a.testBit(f.width - 1)
      val e     = ((a >> f.fracBits) & f.expMask).toInt
      val frac  = a & f.fracMask
      val nan   = f.canonicalNaN
      val NV = FpFlags.Invalid; val DZ = FpFlags.DivByZero
      if (e == f.expMask.toInt && frac != 0)
        return FpResult(nan, if (frac.testBit(f.fracBits - 1)) 0 else NV)
      val isInf  = e == f.expMask.toInt
      val isZero = e == 0 && (frac == 0 || !p.subnormals)
      val negOk  = op == RootOp.Recip
      if (isZero) return op match {
        case RootOp.Sqrt => FpResult(f.zero(sign), 0)
        case _           => FpResult(f.infinity(sign), DZ)
      }
      if (sign && !negOk) return FpResult(nan, NV)
      if (isInf) return op match {
        case RootOp.Sqrt => FpResult(f.infinity(false), 0)
        case _           => FpResult(f.zero(sign), 0)
      }
      // a = A * 2^ea exactly
      val (aSig, ea) = if (e == 0) (frac, 1 - f.bias - f.fracBits) else (frac | (BigInt(1) << f.fracBits), e - f.bias - f.fracBits)
      // sign(n * 2^x - v) for the exact result v
      def cmp(n: BigInt, x: Int): Int = if (n == 0) -1 else op match {
        case RootOp.Sqrt  => cmpScaled(n * n, 2 * x, aSig, ea)
        case RootOp.Recip => cmpScaled(n * aSig, x + ea, BigInt(1), 0)
        case RootOp.Rsqrt => cmpScaled(n * n * aSig, 2 * x + ea, BigInt(1), 0)
      }
      // Binade: largest t with 2^t <= v.
      var lo = -(2 * f.bias + 2 * f.sigBits + 8); var hi = -lo
      require(cmp(1, lo) <= 0 && cmp(1, hi) > 0)
      while (hi - lo > 1) { val mid = (lo + hi) / 2; if (cmp(1, mid) <= 0) lo = mid else hi = mid }
      val t = lo
      def overflow: FpResult = {
        val toInf = rm match {
          case RoundingMode.RNE | RoundingMode.RMM => true
          case RoundingMode.RTZ => false
          case RoundingMode.RDN => sign
          case RoundingMode.RUP => !sign
        }
        FpResult(if (toInf) f.infinity(sign) else f.maxFinite(sign), FpFlags.Overflow | FpFlags.Inexact)
      }
      if (t > f.maxExp) return overflow
      val tiny = t < f.minExp
      if (tiny && !p.subnormals) return FpResult(f.zero(sign), FpFlags.Underflow | FpFlags.Inexact)
      val q = math.max(t - f.fracBits, f.minSubExp)
      var n = BigInt(0)
      for (b <- f.sigBits to 0 by -1) { val c = n.setBit(b); if (cmp(c, q) <= 0) n = c }
      val exact = cmp(n, q) == 0
      val half  = cmp(2 * n + 1, q - 1) // sign of (midpoint - v)
      val up = !exact && (rm match {
        case RoundingMode.RNE => half < 0 || (half == 0 && n.testBit(0))
        case RoundingMode.RMM => half <= 0
        case RoundingMode.RTZ => false
        case RoundingMode.RDN => sign
        case RoundingMode.RUP => !sign
      })
      var m = n + (if (up) 1 else 0); var qq = q
      if (m.bitLength > f.sigBits) { m >>= 1; qq += 1 }
      if (qq + f.fracBits > f.maxExp) return overflow
      val flags = (if (exact) 0 else FpFlags.Inexact) | (if (tiny && !exact) FpFlags.Underflow else 0)
      val sb = if (sign) f.signBit else BigInt(0)
      val bits = if (m.testBit(f.fracBits)) sb | (BigInt(qq + f.fracBits + f.bias) << f.fracBits) | (m & f.fracMask) else sb | m
      FpResult(bits, flags)
    }
  }

  // ---------------------------------------------------------------- JVM oracles (RNE)
  def isNaNBits(f: FloatFormat, b: BigInt): Boolean =
    ((b >> f.fracBits) & f.expMask) == f.expMask && (b & f.fracMask) != 0

  /** float -> bf16, round to nearest even (bit trick; NaNs mapped to the canonical NaN). */
  def floatToBf16(x: Float): BigInt =
    if (x.isNaN) FloatFormat.bf16.canonicalNaN
    else { val b = java.lang.Float.floatToRawIntBits(x); BigInt(((b + 0x7fff + ((b >>> 16) & 1)) >>> 16) & 0xffff) }

  /** float -> fp16, round to nearest even through double arithmetic (Math.rint is RNE). */
  def floatToFp16(x: Float): BigInt = {
    val f = FloatFormat.fp16
    if (x.isNaN) return f.canonicalNaN
    val neg = (java.lang.Float.floatToRawIntBits(x) >>> 31) == 1
    val sb  = if (neg) 0x8000 else 0
    val ax  = math.abs(x.toDouble)
    if (ax >= 65520.0) return BigInt(sb | 0x7c00)
    if (ax == 0.0) return BigInt(sb)
    val q = math.max(Math.getExponent(ax) - 10, -24)
    val r = Math.rint(ax / math.pow(2, q)).toLong // exact scaling, RNE
    val v = r.toDouble * math.pow(2, q)
    if (v < math.pow(2, -14)) BigInt(sb | r.toInt)
    else { val ee = Math.getExponent(v); val fr = (v / math.pow(2, ee - 10)).toLong - 1024; BigInt(sb | ((ee + 15) << 10) | fr.toInt) }
  }

  def bitsToFloat(f: FloatFormat, b: BigInt): Float = f match {
    case FloatFormat.fp32 => java.lang.Float.intBitsToFloat(b.toInt)
    case FloatFormat.bf16 => java.lang.Float.intBitsToFloat(b.toInt << 16)
    case FloatFormat.fp16 =>
      val s = if (b.testBit(15)) -1.0 else 1.0; val e = ((b >> 10) & 0x1f).toInt; val fr = (b & 0x3ff).toInt
      (if (e == 31) { if (fr == 0) s * Double.PositiveInfinity else Double.NaN }
       else if (e == 0) s * fr * math.pow(2, -24) else s * (1024 + fr) * math.pow(2, e - 25)).toFloat
  }

  /** The JVM's own result (IEEE RNE) for sqrt or 1/a, where one exists (fp32, fp64; fp16 and
    * bf16 through float by the 2p+2 rule); None for rsqrt or other formats. */
  def jvmRne(op: RootOp, f: FloatFormat, a: BigInt): Option[BigInt] = {
    def fl(x: Float): Float = op match { case RootOp.Sqrt => Math.sqrt(x.toDouble).toFloat; case _ => 1.0f / x }
    op match {
      case RootOp.Rsqrt => None
      case _ => f match {
        case FloatFormat.fp64 =>
          val d = java.lang.Double.longBitsToDouble(a.toLong)
          val r = if (op == RootOp.Sqrt) Math.sqrt(d) else 1.0 / d
          Some(if (r.isNaN) f.canonicalNaN else BigInt(java.lang.Double.doubleToRawLongBits(r)) & ((BigInt(1) << 64) - 1))
        case FloatFormat.fp32 =>
          val r = fl(bitsToFloat(f, a))
          Some(if (r.isNaN) f.canonicalNaN else BigInt(java.lang.Float.floatToRawIntBits(r)) & 0xffffffffL)
        case FloatFormat.bf16 => Some(floatToBf16(fl(bitsToFloat(f, a))))
        case FloatFormat.fp16 => Some(floatToFp16(fl(bitsToFloat(f, a))))
        case _ => None
      }
    }
  }

  // ---------------------------------------------------------------- operands
  /** Named corner operands of a format (both signs): zeros, infinities, quiet and signaling
    * NaNs, subnormal extremes, normal extremes, 1 and its neighbours, about `powers` powers of two. */
  def corners(f: FloatFormat, powers: Int = 40): Seq[BigInt] = {
    def enc(e: Int, fr: BigInt) = (BigInt(e) << f.fracBits) | fr
    val one = enc(f.bias, 0)
    val pos = Seq(
      BigInt(0), BigInt(1), BigInt(2), BigInt(3), f.fracMask, f.fracMask - 1, BigInt(1) << (f.fracBits - 1),
      enc(1, 0), enc(1, 1), enc(1, f.fracMask), enc(2, 0), enc(2, f.fracMask),
      one, one + 1, one - 1, enc(f.bias + 1, 0), enc(f.bias + 1, 1), enc(f.bias + 1, f.fracMask), enc(f.bias + 2, 0),
      enc(f.bias - 1, 0), enc(f.bias, f.fracMask), enc(f.bias, BigInt(1) << (f.fracBits - 1)),
      enc(f.expMask.toInt - 1, 0), enc(f.expMask.toInt - 1, f.fracMask), enc(f.expMask.toInt - 2, f.fracMask),
      enc(f.expMask.toInt - 1, BigInt(1) << (f.fracBits - 1)),
      f.infinity(false), f.canonicalNaN, f.canonicalNaN | 1, enc(f.expMask.toInt, 1), enc(f.expMask.toInt, f.fracMask >> 1)
    ) ++ (1 until f.expMask.toInt by math.max(1, f.expMask.toInt / powers)).map(enc(_, 0))
    (pos ++ pos.map(_ | f.signBit)).distinct
  }

  /** A random operand: uniform bits, or biased to subnormals, exponent extremes, values near
    * one, exact squares (sqrt exact), short or all-ones fractions. */
  def randomOperand(f: FloatFormat, rng: Random): BigInt = {
    def enc(e: Int, fr: BigInt) = (BigInt(e) << f.fracBits) | (fr & f.fracMask)
    val frac = rng.nextInt(4) match {
      case 0 => f.fracMask ^ (BigInt(1) << rng.nextInt(f.fracBits))
      case 1 => BigInt(1) << rng.nextInt(f.fracBits)
      case _ => BigInt(f.fracBits, rng.self)
    }
    val sgn = if (rng.nextInt(8) == 0) f.signBit else BigInt(0)
    sgn | (rng.nextInt(8) match {
      case 0 => BigInt(f.width - 1, rng.self)                                  // anything, NaNs too
      case 1 => BigInt(rng.nextInt(f.fracBits) + 1, rng.self) & f.fracMask     // subnormal
      case 2 => enc(1 + rng.nextInt(3), frac)                                  // smallest normals
      case 3 => enc(f.expMask.toInt - 1 - rng.nextInt(3), frac)                // largest normals
      case 4 => enc(f.bias - 1 + rng.nextInt(3), frac)                         // near one
      case 5 =>                                                                // exact square
        val h = (f.sigBits + 1) / 2
        val y = (BigInt(1) << (h - 1)) | BigInt(h - 1, rng.self)
        val sq = y * y
        val e = 1 + rng.nextInt(f.expMask.toInt - 2)
        enc(e, (sq << (f.sigBits - sq.bitLength)) & f.fracMask)
      case _ => enc(1 + rng.nextInt(f.expMask.toInt - 1), frac)               // any finite
    })
  }

  def showBits(f: FloatFormat, b: BigInt): String = s"0x${b.toString(16)}"

  // ---------------------------------------------------------------- RTL harness
  def build(op: RootOp, p: FpParams, alg: RootAlgorithm, latency: Int): FpRootUnit = op match {
    case RootOp.Sqrt  => new FpSqrt(p, alg, latency)
    case RootOp.Recip => new FpRecip(p, alg, latency)
    case RootOp.Rsqrt => new FpRsqrt(p, alg, latency)
  }

  /** Streams `vectors` through the DUT, a new input on most cycles, en low now and then
    * (a stall), and checks each output, bits and flags, exactly `latency` enabled cycles
    * after its input against `golden`; valid must follow the same delay. */
  def stream(c: FpRootUnit, vectors: Seq[(BigInt, RoundingMode)], rng: Random,
             golden: (BigInt, RoundingMode) => FpResult): Unit = {
    val f = c.p.format
    val pending = scala.collection.mutable.Queue.fill[Option[(BigInt, RoundingMode)]](c.latency)(None)
    val it = vectors.iterator
    var cycles = 0
    var checked = 0
    c.io.en.poke(true.B); c.io.in.valid.poke(false.B)
    while (it.hasNext || pending.exists(_.isDefined)) {
      val en = rng.nextInt(8) != 0
      // When en is low the input is not taken: poke junk (valid or not) that must be ignored.
      val in = if (en && it.hasNext && rng.nextInt(10) != 0) Some(it.next()) else None
      val junk = !en && rng.nextBoolean()
      c.io.en.poke(en.B)
      c.io.in.valid.poke((in.isDefined || junk).B)
      val (a, rm) = in.getOrElse((BigInt(f.width, rng.self), RoundingMode.all(rng.nextInt(5))))
      c.io.in.bits.a.poke(a.U(f.width.W)); c.io.in.bits.rm.poke(rm.hw)
      if (en) {
        pending.enqueue(in)
        val want = pending.dequeue()
        assert(c.io.out.valid.peek().litToBoolean == want.isDefined, s"cycle $cycles: out.valid should be ${want.isDefined}")
        want.foreach { case (a, rm) =>
          val g = golden(a, rm)
          val bits = c.io.out.bits.bits.peek().litValue; val fl = c.io.out.bits.flags.peek().litValue.toInt
          assert(bits == g.bits && fl == g.flags,
            s"${c.desiredName} a=${showBits(f, a)} $rm: got ${showBits(f, bits)} [${FpFlags.show(fl)}], want ${g.show(f)}")
          checked += 1
        }
      }
      c.clock.step(); cycles += 1
    }
    assert(checked == vectors.size, s"checked $checked of ${vectors.size}")
  }
}
