package collide.fp

import java.math.{BigDecimal => JBD, BigInteger, MathContext}
import collide.fp.model.NewtonRaphsonModel
import collide.testutil.Seeds

/** Exact error measurement of the Newton-Raphson cores (through the golden model, which the
  * RTL matches bit for bit: NewtonRaphsonCoreSpec). Errors are in ulps of the returned w in
  * [1,2), i.e. units of 2^-(n-1). The exact value is a rational (Recip) or the square root
  * of one (Sqrt, Rsqrt): reported errors are exact to 2^-40 ulp, and bound checks compare
  * exactly (through squares for the roots).
  */
object NewtonRaphsonErrorMeter {
  import RootAlgorithm.NewtonRaphson

  /** The exact w (or w^2 for the roots) as num/den, and expDec, for significand `sig`. */
  def exact(op: RootOp, n: Int, sig: BigInt, expOdd: Boolean): (BigInt, BigInt, Boolean) = {
    val one = BigInt(1)
    op match {
      case RootOp.Recip => // 1/m = 2^(n-1)/sig; w = 2/m unless m = 1
        val dec = sig != (one << (n - 1))
        (one << (if (dec) n else n - 1), sig, dec)
      case RootOp.Rsqrt => // x = X/2^(n-1); w^2 = d^2/x
        val x = if (expOdd) sig << 1 else sig
        val dec = x != (one << (n - 1))
        ((if (dec) BigInt(4) else one) << (n - 1), x, dec)
      case RootOp.Sqrt => // w^2 = x
        val x = if (expOdd) sig << 1 else sig
        (x, one << (n - 1), false)
    }
  }

  /** |a/2^k - w| in ulps of w (2^-(n-1)), to within 2^-20 ulp: in double arithmetic while
    * a and w fit it with 20 bits to spare (n <= 32), else through BigInt. */
  def ulpsError(op: RootOp, n: Int, sig: BigInt, expOdd: Boolean, a: BigInt, k: Int): Double =
    if (n <= 32 && a.bitLength <= 52) {
      val m = sig.toDouble / math.pow(2, n - 1)
      val x = if (op != RootOp.Recip && expOdd) 2 * m else m
      val v = op match {
        case RootOp.Recip => 1 / x
        case RootOp.Rsqrt => 1 / math.sqrt(x)
        case RootOp.Sqrt  => math.sqrt(x)
      }
      val w = if (v < 1) 2 * v else v
      math.abs(a.toDouble / math.pow(2, k) - w) * math.pow(2, n - 1)
    } else ulpsErrorExact(op, n, sig, expOdd, a, k)

  /** |a/2^k - w| in ulps of w, to within 2^-40 ulp, in integer arithmetic. */
  def ulpsErrorExact(op: RootOp, n: Int, sig: BigInt, expOdd: Boolean, a: BigInt, k: Int): Double = {
    val (num, den, _) = exact(op, n, sig, expOdd)
    val mc = MathContext.DECIMAL64
    if (op == RootOp.Recip) {
      val diff = (a * den - (num << k)).abs << (n - 1)
      new JBD(diff.bigInteger).divide(new JBD((den << k).bigInteger), mc).doubleValue
    } else {
      val kk = k + 40 + n
      val w = BigInt(((num << (2 * kk)) / den).bigInteger.sqrt()) // floor(w 2^kk), error < 1
      val diff = ((a << (kk - k)) - w).abs << (n - 1)
      new JBD(diff.bigInteger).divide(new JBD((BigInt(1) << kk).bigInteger), mc).doubleValue
    }
  }

  /** Exactly: |a/2^k - w| <= bound ulps (< bound when `strict`). */
  def within(op: RootOp, n: Int, sig: BigInt, expOdd: Boolean, a: BigInt, k: Int, bound: Double,
             strict: Boolean = false): Boolean = {
    def le(c: Int) = if (strict) c < 0 else c <= 0
    val (num, den, _) = exact(op, n, sig, expOdd)
    val mc = MathContext.UNLIMITED
    val av = new JBD(a.bigInteger).divide(new JBD((BigInt(1) << k).bigInteger), mc) // dyadic: exact
    val t  = new JBD(bound).divide(new JBD((BigInt(1) << (n - 1)).bigInteger), mc)
    val lo = av.subtract(t); val hi = av.add(t)
    val N = new JBD(num.bigInteger); val D = new JBD(den.bigInteger)
    if (op == RootOp.Recip) le(lo.multiply(D).compareTo(N)) && le(N.compareTo(hi.multiply(D)))
    else (lo.signum <= 0 || le(lo.multiply(lo).multiply(D).compareTo(N))) &&
      le(N.compareTo(hi.multiply(hi).multiply(D)))
  }

  /** RNE of the core output (RoundIn layout), as RoundRaw does: an n-bit integer, or 2^n
    * when it rounds up to 2. */
  def rne(out: BigInt): BigInt = {
    val top = out >> 2
    val up = out.testBit(1) && (out.testBit(0) || top.testBit(0))
    top + (if (up) 1 else 0)
  }

  final case class Worst(ulps: Double, sig: BigInt, expOdd: Boolean)
  final case class Stats(count: Int, pre: Worst, rne: Worst, outsideBound: Seq[(BigInt, Boolean)],
                         expDecWrong: Seq[(BigInt, Boolean)], notFaithful: Int)

  /** Measures every case; `bound` (ulps after RNE) is checked exactly on every case. */
  def measure(op: RootOp, nr: NewtonRaphson, n: Int, cases: Iterator[(BigInt, Boolean)], bound: Double): Stats = {
    var pre = Worst(-1, 0, false); var post = Worst(-1, 0, false)
    val outside = Seq.newBuilder[(BigInt, Boolean)]; val decWrong = Seq.newBuilder[(BigInt, Boolean)]
    var count = 0; var unfaithful = 0
    for ((sig, odd) <- cases) {
      count += 1
      val (raw, out) = NewtonRaphsonModel.rawAndCore(op, nr, n, sig, odd)
      val dec = raw.expDec
      if (dec != exact(op, n, sig, odd)._3) decWrong += ((sig, odd))
      val ePre = ulpsError(op, n, sig, odd, raw.value, raw.fracBits)
      if (ePre > pre.ulps) pre = Worst(ePre, sig, odd)
      val r = rne(out)
      val ePost = ulpsError(op, n, sig, odd, r, n - 1)
      if (ePost > post.ulps) post = Worst(ePost, sig, odd)
      if (ePost > bound - 1e-5 && !within(op, n, sig, odd, r, n - 1, bound)) outside += ((sig, odd))
      if (ePost > 1 - 1e-5 && !within(op, n, sig, odd, r, n - 1, 1.0, strict = true)) unfaithful += 1
    }
    Stats(count, pre, post, outside.result(), decWrong.result(), unfaithful)
  }

  /** Exhaustive for n <= 16 (every significand, both parities for the roots); otherwise
    * `samples` random significands plus the edges of every seed interval and m = 1, 2 - ulp. */
  def cases(op: RootOp, nr: NewtonRaphson, n: Int, samples: Int, rng: scala.util.Random): Iterator[(BigInt, Boolean)] = {
    val one = BigInt(1)
    val parities = if (op == RootOp.Recip) Seq(false) else Seq(false, true)
    if (n <= 16) {
      for (odd <- parities.iterator; f <- (0L until (1L << (n - 1))).iterator) yield ((one << (n - 1)) + f, odd)
    } else {
      val plan = NewtonRaphsonCore.Plan(op, n, nr)
      val step = one << (n - 1 - plan.s)
      val edges = for {
        odd <- parities; j <- 0 until (1 << plan.s)
        d <- Seq(BigInt(0), BigInt(1), step - 1, step - 2)
      } yield ((one << (n - 1)) + j * step + d, odd)
      val random = Iterator.fill(samples)(((one << (n - 1)) + BigInt(n - 1, rng.self), parities(rng.nextInt(parities.size))))
      edges.iterator.filter(_._1.bitLength == n) ++ random
    }
  }

  def exhaustive(n: Int): Boolean = n <= 16

  /** Two significant digits, rounded up. */
  def roundUp2(x: Double): Double = {
    if (x <= 0) return 0
    val e = math.floor(math.log10(x)).toInt - 1
    val s = math.pow(10, e)
    val r = math.ceil(x / s - 1e-9) * s
    BigDecimal(r).round(new MathContext(2, java.math.RoundingMode.CEILING)).toDouble
  }
}

/** Prints the error table of docs/fp/newton-raphson.md:
  * `sbt "Test/runMain collide.fp.NewtonRaphsonErrorTable"` (-Dcases=N for more samples). */
object NewtonRaphsonErrorTable {
  def main(args: Array[String]): Unit = {
    val rng = Seeds.rng("NewtonRaphsonErrorTable")
    val samples = Seeds.cases(20000)
    println("| sigBits | setting | op | cases | worst before rounding | worst after RNE | measured, rounded up | tested bound (ulpBound) | a priori bound | faithful |")
    println("|---|---|---|---|---|---|---|---|---|---|")
    for ((n, settings) <- NewtonRaphsonBounds.tabulated; nr <- settings; op <- RootOp.all) {
      val st = NewtonRaphsonErrorMeter.measure(op, nr, n, NewtonRaphsonErrorMeter.cases(op, nr, n, samples, rng), Double.MaxValue)
      val kind = if (NewtonRaphsonErrorMeter.exhaustive(n)) "all" else "sampled"
      println(f"| $n | ${nr.name} | ${op.name} | ${st.count} ($kind) | ${st.pre.ulps}%.4f | ${st.rne.ulps}%.4f | " +
        f"${NewtonRaphsonErrorMeter.roundUp2(st.rne.ulps)} | ${NewtonRaphsonBounds.ulpBound(op, nr, n)}%.4g | " +
        f"${NewtonRaphsonBounds.analyticBound(op, nr, n)}%.4g | ${if (NewtonRaphsonBounds.faithful(op, nr, n)) "yes" else "no"} |")
    }
    println()
    println("| sigBits | cheapest faithful sqrt | recip | rsqrt | all three |")
    println("|---|---|---|---|---|")
    for (n <- Seq(8, 11, 16, 24, 32, 53)) {
      val per = RootOp.all.map(op => NewtonRaphsonBounds.faithfulSettings(op, n).headOption.fold("none")(_.name))
      println(s"| $n | ${per.mkString(" | ")} | ${NewtonRaphsonBounds.cheapestFaithful(n).fold("none")(_.name)} |")
    }
  }
}
