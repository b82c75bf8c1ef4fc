package collide.pairs

import collide.fp.FloatFormat
import collide.pairs.model._
import collide.scpu.ScpuConfig
import collide.scpu.model.ScpuModel

/** Writes the golden vectors of the pair kinds beyond spheres, which the C++ host checks its
  * binary32 and binary64 references against (test/vectors/<kind>-<format>.csv, read by
  * test/test_pair_kinds.cpp): each kind's hard cases with finite inputs and seeded random pairs,
  * inputs and the golden model's contact as C99 hex floats. PairVectorsSpec checks that the
  * committed files are what this writes.
  *
  * usage: tools/sbt "Test/runMain collide.pairs.PairVectorsWriter [kind] [fp32|fp64]"
  */
object PairVectorsWriter {
  val formats: Seq[(String, ScpuConfig)] = Seq("fp32" -> ScpuConfig.fp32, "fp64" -> ScpuConfig.fp64)

  /** One kind: its input columns, and its rows (inputs, hit, contact) for a configuration. */
  final case class Kind(name: String, columns: Seq[String], rows: (ScpuConfig, Int, scala.util.Random) => Seq[(Seq[BigInt], Boolean, Seq[BigInt])])

  val kinds: Seq[Kind] = Seq(
    Kind("sphere-plane", Seq("cx", "cy", "cz", "r", "nx", "ny", "nz", "d"), (cfg, n, rng) => {
      val vec = new SpherePlaneVectors(cfg)
      val model = new SpherePlaneModel(cfg)
      val pairs = vec.hardCases.map(_._2) ++ Seq.tabulate(n)(i => vec.random(rng, if (i % 4 == 0) 1e3 else 10)) ++
        Iterator.continually(vec.raw(rng)).filter(p => finite(cfg.format, p.fields)).take(n / 4)
      pairs.filter(p => finite(cfg.format, p.fields)).map { p => val r = model.collide(p); (p.fields, r.hit, r.fields) }
    }),
    Kind("capsule-sphere", Seq("cx", "cy", "cz", "ax", "ay", "az", "lz", "rc", "sx", "sy", "sz", "rs"), (cfg, n, rng) => {
      val vec = new CapsuleSphereVectors(cfg)
      val model = new CapsuleSphereModel(cfg)
      val pairs = vec.hardCases.map(_._2) ++ Seq.tabulate(n)(i => vec.random(rng, if (i % 4 == 0) 1e3 else 10)) ++
        Iterator.continually(vec.raw(rng)).filter(p => finite(cfg.format, p.fields)).take(n / 4)
      pairs.filter(p => finite(cfg.format, p.fields)).map { p => val r = model.collide(p); (p.fields, r.hit, r.fields) }
    }))

  def finite(f: FloatFormat, xs: Seq[BigInt]): Boolean = xs.forall(x => ((x >> f.fracBits) & f.expMask) != f.expMask)
  def path(kind: String, format: String): String = s"test/vectors/$kind-$format.csv"

  def hex(f: FloatFormat, bits: BigInt): String =
    if (f == FloatFormat.fp32) java.lang.Float.toHexString(java.lang.Float.intBitsToFloat(bits.toInt))
    else java.lang.Double.toHexString(ScpuModel.toDouble(f, bits))

  /** The file's text for one kind and configuration (fixed seed: the file is committed). */
  def text(kind: Kind, cfg: ScpuConfig, n: Int = 2000, seed: Long = 20261208L): String = {
    val f = cfg.format
    val header = (kind.columns ++ Seq("hit", "px", "py", "pz", "qx", "qy", "qz", "depth")).mkString(",")
    val lines = kind.rows(cfg, n, new scala.util.Random(seed)).map { case (in, hit, out) =>
      (in.map(hex(f, _)) ++ Seq(if (hit) "1" else "0") ++ out.map(hex(f, _))).mkString(",")
    }
    (header +: lines).mkString("", "\n", "\n")
  }

  def main(args: Array[String]): Unit =
    for (kind <- kinds if args.lift(0).forall(_ == kind.name); (name, cfg) <- formats if args.lift(1).forall(_ == name)) {
      val out = path(kind.name, name)
      java.nio.file.Files.write(java.nio.file.Paths.get(out), text(kind, cfg).getBytes("UTF-8"))
      println(s"wrote $out")
    }
}
