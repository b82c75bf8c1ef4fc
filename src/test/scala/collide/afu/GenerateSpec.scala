package collide.afu

import org.scalatest.flatspec.AnyFlatSpec
import collide.Generate

/** The generator CLI's configuration handling, manifest and header (no hardware built). */
class GenerateSpec extends AnyFlatSpec {
  behavior of "collide.Generate"

  private def cfg(args: String*) =
    scopt.OParser.parse(Generate.parser, args, Generate.Opts()).map(Generate.config).getOrElse(fail(s"parse: $args"))

  it should "build the presets and name derived configurations by every parameter" in {
    assert(cfg().contains(AfuConfig.default))
    assert(cfg("--preset", "fp16").contains(AfuConfig.fp16))
    val c = cfg("--scpus", "4", "--format", "fp16").toOption.get
    assert(c.scpus == 4 && c.scpu.format == collide.fp.FloatFormat.fp16 && !c.isPreset)
    assert(c.id == "n4_fp16_s1024_r64_w64_t6_rep")
    val d = cfg("--scpus", "4", "--format", "fp16", "--max-spheres", "2048").toOption.get
    assert(d.id != c.id && d.puc.name != c.puc.name, "two configurations must not share module names")
    assert(cfg("--format", "e6m12").toOption.get.scpu.format == collide.fp.FloatFormat(6, 12))
    assert(cfg("--scpu", "fp32:rm=rtz").toOption.get.scpu.rounding == collide.fp.RoundingMode.RTZ)
  }

  it should "refuse a configuration that cannot be built, naming the flag and the problem" in {
    def err(args: String*)(flag: String, words: String*) = {
      val e = cfg(args: _*)
      assert(e.isLeft, s"$args should fail")
      val m = e.swap.toOption.get
      assert(m.startsWith(flag) && words.forall(m.contains), s"message '$m' should start with $flag and say ${words.mkString(", ")}")
    }
    err("--scpus", "0")("--scpus", "1..64")
    err("--scpus", "65")("--scpus", "1..64")
    err("--max-spheres", "1000")("--max-spheres", "power of two")
    err("--max-reads", "65")("--max-reads", "2^tagBits")
    err("--preset", "nope")("--preset", "unknown")
    err("--format", "e20m5")("--format", "exponent")
    err("--scpu", "fp32:tag=8")("--scpu", "tagBits")
    err("--ram-ports", "banked")("--ram-ports", "not implemented")
  }

  it should "write every CSR, status offset and flag into the manifest and the header" in {
    val c = AfuConfig.fp64.copy(scpus = 3)
    val m = AfuManifest.json(c, "cmd")
    val h = AfuManifest.header(c, "cmd")
    for ((k, v) <- Csr.all) { assert(m("csr")(k).num == v); assert(h.contains(s"CSR_$k = ${v}u;")) }
    for ((k, v) <- StatusLine.all) { assert(m("status")(k).num == v); assert(h.contains(s"STATUS_$k = ${v}u;")) }
    for ((k, v) <- ErrorFlags.all) assert(h.contains(s"ERR_$k = ${v}u;"))
    assert(m("link")("format").str == "binary64" && h.contains("records_per_line = 1;") && h.contains("spheres_per_line = 2;"))
    assert(m("afu")("ram")("sphereTableBits").num == 3.0 * 1024 * 4 * 64)
    assert(m("scpu")("latency").num == c.scpu.latency)
  }
}
