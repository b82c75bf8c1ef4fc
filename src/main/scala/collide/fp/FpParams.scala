package collide.fp

/** What an arithmetic unit computes (its semantics), apart from how it is built
  * (latency, algorithm choice for roots, which live with each operator's parameters).
  *
  * @param format      the compute format
  * @param subnormals  true: subnormal inputs and results are kept (IEEE gradual underflow);
  *                    false: subnormal inputs are read as zero of the same sign and results
  *                    that are tiny before rounding become zero of the same sign with
  *                    underflow and inexact raised (flush-to-zero, DAZ+FTZ).
  */
final case class FpParams(format: FloatFormat, subnormals: Boolean = true) {
  def width: Int   = format.width
  def name: String = format.name + (if (subnormals) "" else "_ftz")
}

object FpParams {
  val fp32 = FpParams(FloatFormat.fp32)
  val fp64 = FpParams(FloatFormat.fp64)
}

/** How sqrt, reciprocal and reciprocal square root are computed. */
sealed trait RootAlgorithm { def name: String }
object RootAlgorithm {
  /** Restoring digit recurrence, one result bit per step: correctly rounded in every mode. */
  case object DigitRecurrence extends RootAlgorithm { val name = "dr" }
  /** Table-seeded Newton-Raphson in fixed point: `seedBits` index bits of the seed table,
    * `iterations` refinement steps. Not correctly rounded; the error bound is measured and
    * documented per setting (docs/fp.md).
    */
  final case class NewtonRaphson(seedBits: Int, iterations: Int) extends RootAlgorithm {
    require(seedBits >= 3 && seedBits <= 12, s"Newton-Raphson seed bits must be 3..12, got $seedBits")
    require(iterations >= 0 && iterations <= 4, s"Newton-Raphson iterations must be 0..4, got $iterations")
    val name = s"nr${seedBits}x$iterations"
  }

  def parse(s: String): Either[String, RootAlgorithm] = {
    val Nr = """nr(\d+)x(\d+)""".r
    s.trim.toLowerCase match {
      case "dr" | "digit-recurrence" => Right(DigitRecurrence)
      case Nr(a, b) =>
        try Right(NewtonRaphson(a.toInt, b.toInt))
        catch { case e: IllegalArgumentException => Left(s"algorithm '$s': ${e.getMessage.stripPrefix("requirement failed: ")}") }
      case _ => Left(s"algorithm '$s': expected 'dr' or 'nr<seedBits>x<iterations>' (e.g. nr8x2)")
    }
  }
}

/** The three root-type operators that share the significand cores (digit recurrence and
  * Newton-Raphson). A core sees a significand m in [1,2) and, for Sqrt/Rsqrt, whether the
  * exponent is odd (then it works on x = 2m in [2,4)); Recip ignores expOdd (x = m).
  */
sealed trait RootOp { def name: String }
object RootOp {
  case object Sqrt  extends RootOp { val name = "sqrt" }
  case object Recip extends RootOp { val name = "recip" }
  case object Rsqrt extends RootOp { val name = "rsqrt" }
  val all: Seq[RootOp] = Seq(Sqrt, Recip, Rsqrt)
}
