package collide.fp.report

import collide.fp._
import collide.fp.model._
import java.math.{MathContext, BigDecimal => JBigDecimal}

/** Prints, per operator and configuration, latency, throughput and the error against the
  * exact result (in ulps of the format), measured exhaustively for unary operators on 16-bit
  * formats and on seeded samples otherwise. Every figure is measured by running the golden
  * model, which the specs prove bit-exact with the RTL.
  *
  * usage: sbt "runMain collide.fp.report.FpReport [--out FILE.md] [--samples N] [--seed S]"
  */
object FpReport {
  private val mc = new MathContext(120)

  /** A unary or binary operation, its latency in this report, and its exact reference. */
  final case class Op(name: String, alg: String, latency: Int, arity: Int,
                      run: (FpParams, Seq[BigInt]) => FpResult,
                      exact: Seq[BigDecimal] => Option[JBigDecimal])

  /** Latencies used for the table: one reasonable pipelining per operator (every one of them
    * is a parameter; throughput is one result per cycle at any latency). */
  def rootLatency(f: FloatFormat, alg: RootAlgorithm): Int = alg match {
    case RootAlgorithm.DigitRecurrence => 2 + (f.sigBits + 3) / 4 // about 4 recurrence steps a cycle
    case RootAlgorithm.NewtonRaphson(_, it) => 2 + 1 + 2 * it     // seed, then two multiplies a step
  }

  private def sqrtExact(x: JBigDecimal): Option[JBigDecimal] =
    if (x.signum < 0) None else Some(x.sqrt(mc))

  def ops(f: FloatFormat): Seq[Op] = {
    val rne = RoundingMode.RNE
    val roots = Seq[RootAlgorithm](RootAlgorithm.DigitRecurrence) ++
      Seq(RootAlgorithm.NewtonRaphson(6, 1), RootAlgorithm.NewtonRaphson(8, 1),
          RootAlgorithm.NewtonRaphson(8, 2), RootAlgorithm.NewtonRaphson(10, 2))
    Seq(
      Op("add", "-", 2, 2, (p, a) => FpAddModel(p, a(0), a(1), rne), a => Some(a(0).bigDecimal.add(a(1).bigDecimal))),
      Op("mul", "-", 2, 2, (p, a) => FpMulModel(p, a(0), a(1), rne), a => Some(a(0).bigDecimal.multiply(a(1).bigDecimal)))
    ) ++ roots.flatMap { alg =>
      Seq(
        Op("sqrt", alg.name, rootLatency(f, alg), 1, (p, a) => FpSqrtModel(p, alg, a(0), rne), a => sqrtExact(a(0).bigDecimal)),
        Op("recip", alg.name, rootLatency(f, alg), 1, (p, a) => FpRecipModel(p, alg, a(0), rne),
          a => if (a(0).signum == 0) None else Some(JBigDecimal.ONE.divide(a(0).bigDecimal, mc))),
        Op("rsqrt", alg.name, rootLatency(f, alg), 1, (p, a) => FpRsqrtModel(p, alg, a(0), rne),
          a => if (a(0).signum <= 0) None else sqrtExact(a(0).bigDecimal).map(s => JBigDecimal.ONE.divide(s, mc)))
      )
    }
  }

  final case class Stats(cases: Long, worst: Double, mean: Double, worstInput: Seq[BigInt])

  /** Error of a finite result against the exact value, in ulps of the exact value. */
  def ulpError(f: FloatFormat, result: JBigDecimal, exact: JBigDecimal): Double = {
    val mag = exact.abs
    val e = if (mag.signum == 0) f.minExp else math.max(java.lang.Math.getExponent(mag.doubleValue), f.minExp)
    val ulp = SoftFloat.exactDecimal(1, e - f.fracBits).bigDecimal
    result.subtract(exact).abs.divide(ulp, new MathContext(20)).doubleValue
  }

  def measure(p: FpParams, op: Op, inputs: Iterator[Seq[BigInt]]): Stats = {
    var n = 0L; var worst = 0.0; var sum = 0.0; var worstIn = Seq.empty[BigInt]
    for (in <- inputs) {
      val vals = in.map(SoftFloat.toBigDecimal(p, _))
      if (vals.forall(_.isDefined)) {
        val r = op.run(p, in)
        for (ex <- op.exact(vals.map(_.get)); rv <- SoftFloat.toBigDecimal(p, r.bits)) {
          if (ex.abs.compareTo(SoftFloat.toBigDecimal(p, p.format.maxFinite(false)).get.bigDecimal) <= 0) {
            val err = ulpError(p.format, rv.bigDecimal, ex)
            n += 1; sum += err
            if (err > worst) { worst = err; worstIn = in }
          }
        }
      }
    }
    Stats(n, worst, if (n == 0) 0 else sum / n, worstIn)
  }

  def main(args: Array[String]): Unit = {
    def arg(name: String): Option[String] = args.sliding(2).collectFirst { case Array(`name`, v) => v }
    val samples = arg("--samples").map(_.toInt).getOrElse(20000)
    val seed    = arg("--seed").map(_.toLong).getOrElse(1L)
    val formats = arg("--formats").map(_.split(",").toSeq.map(s => FloatFormat.parse(s).fold(e => sys.error(e), identity)))
      .getOrElse(FloatFormat.presets.map(_._2))
    val sb = new StringBuilder
    def line(s: String): Unit = { println(s); sb ++= s + "\n" }
    line(s"# Floating-point operators: latency, throughput, error against the exact result")
    line("")
    line(s"Round to nearest even, subnormals kept. Error in ulps of the exact result; unary operators on 16-bit")
    line(s"formats are measured on all 65,536 inputs, everything else on $samples seeded random operands (seed $seed).")
    line(s"Throughput is one result per cycle for every operator at every latency (fully pipelined).")
    line("")
    line("| format | operator | algorithm | latency (cycles) | throughput (/cycle) | inputs measured | worst error (ulp) | mean error (ulp) |")
    line("|---|---|---|---:|---:|---:|---:|---:|")
    for (f <- formats; op <- ops(f)) {
      val p = FpParams(f)
      val rng = new scala.util.Random(seed)
      val exhaustive = op.arity == 1 && f.width <= 16
      def rnd(): BigInt = BigInt(f.width, rng.self)
      val inputs: Iterator[Seq[BigInt]] =
        if (exhaustive) Iterator.range(0, 1 << f.width).map(i => Seq(BigInt(i)))
        else Iterator.fill(if (f.width > 32 && op.arity == 1) samples / 2 else samples)(Seq.fill(op.arity)(rnd()))
      val s = measure(p, op, inputs)
      line(f"| ${f.name} | ${op.name} | ${op.alg} | ${op.latency} | 1 | ${s.cases}%,d | ${s.worst}%.4f | ${s.mean}%.4f |")
    }
    arg("--out").foreach { path =>
      val w = new java.io.PrintWriter(path)
      try w.write(sb.toString) finally w.close()
    }
  }
}
