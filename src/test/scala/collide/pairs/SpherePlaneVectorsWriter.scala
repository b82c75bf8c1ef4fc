package collide.pairs

import collide.fp.FloatFormat
import collide.pairs.model._
import collide.scpu.ScpuConfig
import collide.scpu.model.ScpuModel

/** Writes the sphere/plane golden vectors the C++ host checks its binary32 and binary64
  * references against (test/vectors/sphere-plane-fp32.csv and -fp64.csv): the hard cases with
  * finite inputs and seeded random pairs, inputs and SpherePlaneModel's outputs as C99 hex
  * floats. SpherePlaneVectorsSpec checks the committed files are what this writes.
  *
  * usage: tools/sbt "Test/runMain collide.pairs.SpherePlaneVectorsWriter [fp32|fp64] [out.csv]"
  */
object SpherePlaneVectorsWriter {
  val header = "cx,cy,cz,r,nx,ny,nz,d,hit,px,py,pz,qx,qy,qz,depth"
  val configs: Map[String, ScpuConfig] = Map("fp32" -> ScpuConfig.fp32, "fp64" -> ScpuConfig.fp64)
  def path(name: String): String = s"test/vectors/sphere-plane-$name.csv"

  def hex(f: FloatFormat, bits: BigInt): String =
    if (f == FloatFormat.fp32) java.lang.Float.toHexString(java.lang.Float.intBitsToFloat(bits.toInt))
    else java.lang.Double.toHexString(ScpuModel.toDouble(f, bits))

  /** The file's text for one configuration (fixed seed: the file is committed). */
  def text(cfg: ScpuConfig, n: Int = 2000, seed: Long = 20261208L): String = {
    val vec = new SpherePlaneVectors(cfg)
    val rng = new scala.util.Random(seed)
    val f = cfg.format
    def finite(p: SpherePlanePair) = p.fields.forall(x => ((x >> f.fracBits) & f.expMask) != f.expMask)
    val pairs = vec.hardCases.map(_._2).filter(finite) ++ Seq.tabulate(n)(i => vec.random(rng, if (i % 4 == 0) 1e3 else 10)) ++
      Iterator.continually(vec.raw(rng)).filter(finite).take(n / 4)
    val model = new SpherePlaneModel(cfg)
    val lines = pairs.map { p =>
      val r = model.collide(p)
      (p.fields.map(hex(f, _)) ++ Seq(if (r.hit) "1" else "0") ++ r.fields.map(hex(f, _))).mkString(",")
    }
    (header +: lines).mkString("", "\n", "\n")
  }

  def main(args: Array[String]): Unit = {
    val names = args.lift(0).map(Seq(_)).getOrElse(configs.keys.toSeq.sorted)
    for (name <- names) {
      val cfg = configs.getOrElse(name, sys.error(s"unknown configuration '$name' (known: ${configs.keys.mkString(", ")})"))
      val out = args.lift(1).getOrElse(path(name))
      java.nio.file.Files.write(java.nio.file.Paths.get(out), text(cfg).getBytes("UTF-8"))
      println(s"wrote ${out}")
    }
  }
}
