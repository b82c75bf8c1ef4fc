package collide.scpu

import collide.scpu.model._

/** ODE's dCollideSpheres in plain JVM float arithmetic (IEEE binary32, round to nearest even,
  * no contraction into FMA): the independent oracle for the fp32 correctly rounded RNE preset.
  * Shares no code with the golden model or the RTL. As in the SCPU, a NaN distance is no
  * contact; a hit's fields are returned as binary32 bit patterns.
  */
object FloatOde {
  final case class Result(hit: Boolean, kind: Int, fields: Seq[Int])

  def collide(x1: Float, y1: Float, z1: Float, r1: Float, x2: Float, y2: Float, z2: Float, r2: Float): Result = {
    val dx = x1 - x2
    val dy = y1 - y2
    val dz = z1 - z2
    // Math.sqrt of the exact double of a float, rounded to float: correctly rounded (p = 24,
    // double has 53 >= 2*24 + 2 bits).
    val d = math.sqrt((dx * dx + dy * dy + dz * dz).toDouble).toFloat
    def bits(v: Float) = java.lang.Float.floatToRawIntBits(v)
    if (!(d <= r1 + r2)) Result(hit = false, 0, Seq.fill(7)(0))
    else if (d <= 0) Result(hit = true, 2, Seq(x1, y1, z1, 1.0f, 0.0f, 0.0f, r1 + r2).map(bits))
    else {
      val inv = 1.0f / d
      val nx = dx * inv; val ny = dy * inv; val nz = dz * inv
      val k = 0.5f * (r2 - r1 - d)
      Result(hit = true, 1, Seq(x1 + nx * k, y1 + ny * k, z1 + nz * k, nx, ny, nz, r1 + r2 - d).map(bits))
    }
  }

  def collide(p: ScpuPair): Result = {
    val v = p.fields.map(b => java.lang.Float.intBitsToFloat(b.toInt))
    collide(v(0), v(1), v(2), v(3), v(4), v(5), v(6), v(7))
  }

  /** Whether a golden/RTL result equals this oracle's, NaNs compared as NaNs (the JVM keeps
    * payloads, the operators return the canonical NaN). */
  def agrees(r: ScpuResult, o: Result): Boolean = {
    def same(a: BigInt, b: Int): Boolean = {
      val fa = java.lang.Float.intBitsToFloat(a.toInt)
      val fb = java.lang.Float.intBitsToFloat(b)
      (fa.isNaN && fb.isNaN) || a.toInt == b
    }
    r.hit == o.hit && r.kind == o.kind && r.fields.zip(o.fields).forall { case (a, b) => same(a, b) }
  }
}
