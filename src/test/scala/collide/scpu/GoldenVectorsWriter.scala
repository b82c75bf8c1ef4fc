package collide.scpu

import collide.fp.FpFlags
import collide.scpu.model._

/** Writes the golden vectors the C++ host checks the Verilated AFU and its record decoders
  * against (test/vectors/<preset>.csv, format in docs/host.md): the hard cases plus seeded
  * random pairs, inputs and expected outputs as C99 hex floats of the link format's values,
  * with the derived record's d and w, all produced by the Scala golden model.
  *
  * usage: tools/sbt "Test/runMain collide.scpu.GoldenVectorsWriter [preset] [out.csv] [randomPairs] [seed]"
  */
object GoldenVectorsWriter {
  def hex32(bits: BigInt): String = java.lang.Float.toHexString(java.lang.Float.intBitsToFloat(bits.toInt))
  /** The exact value of a link word as a hex float (binary32 as Float.toHexString prints it). */
  def hex(lf: collide.fp.FloatFormat, bits: BigInt): String =
    if (lf == collide.fp.FloatFormat.fp32) hex32(bits) else java.lang.Double.toHexString(ScpuModel.toDouble(lf, bits))

  /** The dense record's flags byte (docs/afu-interface.md). */
  def recordFlags(r: ScpuResult): Int =
    (if (r.hit) 1 else 0) | (r.kind << 1) | (if (r.nonFinite) 1 << 3 else 0) |
      (if ((r.flags & (FpFlags.Overflow | FpFlags.Invalid)) != 0) 1 << 4 else 0)

  def main(args: Array[String]): Unit = {
    val preset = args.lift(0).getOrElse("fp32")
    val out    = args.lift(1).getOrElse(s"test/vectors/${if (preset == "fp32") "fp32_default" else preset}.csv")
    val n      = args.lift(2).map(_.toInt).getOrElse(3000)
    val seed   = args.lift(3).map(_.toLong).getOrElse(20261122L)
    val cfg = ScpuConfig.parse(preset).fold(e => sys.error(e), identity)
    val vec   = new ScpuVectors(cfg)
    val model = ScpuModel(cfg)
    val rng   = new scala.util.Random(seed)
    // Every hard case whose inputs are finite (the host reads inputs with strtof, which
    // handles nan/inf too, but a non-finite pair's outputs are NaN patterns we do not pin here).
    val pairs = (vec.hardCases ++ vec.linkCases).map(_._2) ++ Seq.fill(n)(vec.mixed(rng))
    val dir = new java.io.File(out).getParentFile
    if (dir != null) dir.mkdirs()
    val w = new java.io.PrintWriter(out)
    try {
      val lf = cfg.linkFormat
      w.println("x1,y1,z1,r1,x2,y2,z2,r2,hit,px,py,pz,nx,ny,nz,depth,flags,d,w")
      for (p <- pairs) {
        val r = model.collide(p)
        w.println((p.fields.map(hex(lf, _)) ++ Seq(if (r.hit) "1" else "0") ++ r.fields.map(hex(lf, _)) ++
          Seq(recordFlags(r).toString) ++ r.derived.map(hex(lf, _))).mkString(","))
      }
    } finally w.close()
    println(s"wrote ${pairs.size} golden vectors for ${cfg.name} to $out")
  }
}
