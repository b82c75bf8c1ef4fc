package collide.scpu

import java.math.{MathContext, BigDecimal => JBigDecimal}
import collide.fp._
import collide.fp.model._
import collide.scpu.model._

/** Exact arithmetic on compute-format values (BigDecimal, MathContext.UNLIMITED) for the
  * properties: the hit decision, the normal's length, the grazing band.
  */
object ScpuExact {
  private val U = MathContext.UNLIMITED

  def value(p: FpParams, bits: BigInt): Option[JBigDecimal] = SoftFloat.toBigDecimal(p, bits).map(_.bigDecimal)

  /** 2^k exactly. */
  def pow2(k: Int): JBigDecimal =
    if (k >= 0) new JBigDecimal(java.math.BigInteger.ONE.shiftLeft(k)) else JBigDecimal.ONE.divide(new JBigDecimal(java.math.BigInteger.ONE.shiftLeft(-k)), U)

  /** The exact decision on the compute-format inputs, or None for a non-finite input:
    * |p1 - p2|^2 <= (r1 + r2)^2 with r1 + r2 >= 0. Also returns how far from grazing the
    * pair is (see within). */
  final case class Decision(hit: Boolean, d2: JBigDecimal, rs: JBigDecimal) {
    def rs2: JBigDecimal = rs.multiply(rs, U)
    /** Whether |d - rs| <= rel * max(d, |rs|) + abs, d = sqrt(d2). Only the band's edge
      * uses a rounded square root (60 digits); the decision itself is exact. */
    def within(rel: JBigDecimal, abs: JBigDecimal): Boolean = {
      val d = d2.sqrt(new MathContext(60))
      val diff = d.subtract(rs, U).abs()
      val m = d.max(rs.abs())
      diff.compareTo(m.multiply(rel, U).add(abs, U)) <= 0
    }
  }

  def decision(p: FpParams, inputs: Seq[BigInt]): Option[Decision] = {
    val vs = inputs.map(value(p, _))
    if (vs.exists(_.isEmpty)) None
    else {
      val Seq(x1, y1, z1, r1, x2, y2, z2, r2) = vs.map(_.get)
      val dx = x1.subtract(x2, U); val dy = y1.subtract(y2, U); val dz = z1.subtract(z2, U)
      val d2 = dx.multiply(dx, U).add(dy.multiply(dy, U), U).add(dz.multiply(dz, U), U)
      val rs = r1.add(r2, U)
      val hit = rs.signum >= 0 && d2.compareTo(rs.multiply(rs, U)) <= 0
      Some(Decision(hit, d2, rs))
    }
  }

  /** |n|^2 - 1 exactly, for a normal given as compute-format bit patterns. */
  def normSqMinusOne(p: FpParams, n: Seq[BigInt]): Option[JBigDecimal] = {
    val vs = n.map(value(p, _))
    if (vs.exists(_.isEmpty)) None
    else Some(vs.map(_.get).map(v => v.multiply(v, U)).reduce(_.add(_, U)).subtract(JBigDecimal.ONE, U))
  }
}
