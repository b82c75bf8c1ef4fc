package collide.scpu

import org.scalatest.flatspec.AnyFlatSpec
import collide.fp._

class ScpuConfigSpec extends AnyFlatSpec {
  behavior of "ScpuConfig"

  it should "default to the fp32 correctly rounded RNE preset" in {
    val c = ScpuConfig()
    assert(c == ScpuConfig.fp32 && c.format == FloatFormat.fp32 && c.rounding == RoundingMode.RNE)
    assert(c.sqrtAlg == RootAlgorithm.DigitRecurrence && c.recipAlg == RootAlgorithm.DigitRecurrence)
    assert(c.distance == DistanceMethod.SqrtThenRecip && c.isPreset && c.id == "fp32")
  }

  it should "carry fp16 and bf16 as themselves, binary32 up to fp32 and binary64 beyond" in {
    for (c <- ScpuConfig.all) {
      val want = if (c.format == FloatFormat.fp16 || c.format == FloatFormat.bf16) c.format
        else if (c.format == FloatFormat.fp64) FloatFormat.fp64 else FloatFormat.fp32
      assert(c.linkFormat == want, c.name)
    }
    assert(ScpuConfig.fp16.linkWidth == 16 && ScpuConfig.fp64.linkWidth == 64)
    assert(ScpuConfig.fp16.copy(link = Some(FloatFormat.fp32)).linkWidth == 32)
    assert(ScpuConfig.parse("fp32:link=fp16").isLeft && ScpuConfig.parse("fp16:link=bf16").isLeft)
    assert(ScpuConfig.parse("fp24:link=fp24").swap.toOption.get.contains("not one the host can carry"))
    assert(ScpuConfig.fp32.copy(format = FloatFormat(9, 20)).linkFormat == FloatFormat.fp64)
  }

  it should "add up the per-stage latencies along the critical path" in {
    for (c <- ScpuConfig.all) {
      assert(c.latency == c.inLatency + c.coreLatency + c.outLatency, c.name)
      assert(c.coreLatency >= c.diffLatency + c.dLatency + c.addLatency + 2 * c.mulLatency + c.addLatency, c.name)
    }
    val c = ScpuConfig.fp32
    // fp32: no conversion; sub 1, squares 1, two adds 2, sqrt 7, recip 7, normal 1, n*k 1, pos 1.
    assert(c.cvtLat == 0 && c.sqrtLat == 7 && c.recipLat == 7)
    assert(c.latency == 1 + (1 + 2) + 7 + 7 + 1 + 1 + 1)
    assert(ScpuConfig.fp16.cvtLat == 0 && ScpuConfig.fp16.latency == ScpuConfig.fp16.coreLatency)
    assert(ScpuConfig.fp24.cvtLat == 1 && ScpuConfig.fp24.latency == ScpuConfig.fp24.coreLatency + 2)
  }

  it should "name every preset distinctly and find each by name" in {
    assert(ScpuConfig.all.map(_.name).distinct.size == ScpuConfig.all.size)
    assert(ScpuConfig.all.map(_.id).distinct.size == ScpuConfig.all.size)
    for (c <- ScpuConfig.all) assert(ScpuConfig.parse(c.name) == Right(c))
    val names = ScpuConfig.all.map(_.name).toSet
    assert(Set("fp32", "fp32-rsqrt-dr", "fp32-nr", "fp32-robust", "fp64", "fp24", "fp16", "bf16", "fp16-robust").subsetOf(names))
  }

  it should "parse options after a preset and give the result its own module name" in {
    val r = ScpuConfig.parse("fp16:rm=RTZ:distance=robust:sqrt=nr8x2:add=2:subnormals=off")
    assert(r.isRight, r)
    val c = r.toOption.get
    assert(c.format == FloatFormat.fp16 && c.rounding == RoundingMode.RTZ && c.distance == DistanceMethod.Robust)
    assert(c.sqrtAlg == RootAlgorithm.NewtonRaphson(8, 2) && c.addLatency == 2 && !c.subnormals)
    assert(!c.isPreset && c.id != ScpuConfig.fp16.id && c.id.startsWith("fp16_"))
    assert(ScpuConfig.parse("fp32:format=e8m16").toOption.get.format == FloatFormat.fp24)
  }

  it should "derive every operator's latency from a clock (mhz=F), per family, with later options overriding" in {
    val c = ScpuConfig.parse("fp32:mhz=200").fold(e => fail(e), identity)
    val fam = FpgaFamily.default
    // FpAdd and FpMul at the smallest latency whose estimated stages fit the period, and that
    // latency is what separates them from a shallower one.
    assert(Right(c.addLatency) == FpAdd.latencyFor(c.params, fam, 200) && Right(c.mulLatency) == FpMul.latencyFor(c.params, fam, 200))
    for ((l, d) <- Seq(c.addLatency -> FpAdd.delays(c.params, fam), c.mulLatency -> FpMul.delays(c.params, fam))) {
      assert(Pipeline.longestRun(l, d) <= fam.budget(200))
      assert(Pipeline.longestRun(l - 1, d) > fam.budget(200))
    }
    // Roots: every iteration of the digit recurrence, its initial state, and each of the unpack's
    // and rounder's pieces registered.
    assert(c.sqrtLat == 24 + 1 + 7 && c.recipLat == 24 + 1 + 7)
    assert(c.latency > ScpuConfig.fp32.latency && c.id != ScpuConfig.fp32.id)
    // A slower clock needs no more registers; ECP5 cuts its multipliers into 18-bit tiles.
    val slow = ScpuConfig.parse("fp32:mhz=50").toOption.get
    assert(slow.addLatency <= c.addLatency && slow.mulLatency <= c.mulLatency)
    val ecp5 = ScpuConfig.parse("fp32:family=ecp5:mhz=100").toOption.get
    assert(ecp5.family == FpgaFamily.ecp5 && ecp5.mulLatency == FpMul.latencyFor(ecp5.params, FpgaFamily.ecp5, 100).toOption.get)
    assert(ecp5.describe.contains("family=ecp5"))
    assert(ScpuConfig.parse("fp32:mhz=200:add=3").toOption.get.addLatency == 3)
  }

  it should "refuse a clock that an operator's single stage cannot reach, naming the operator and the numbers" in {
    def err(s: String) = ScpuConfig.parse(s).swap.getOrElse(fail(s"'$s' parsed"))
    val e = err("fp32:mhz=400")
    assert(e.contains("at 400.0 MHz on cyclonev") && e.contains("has a stage of") && e.contains("ps a period leaves"), e)
    assert(err("fp32:mhz=0").contains("option mhz needs a clock above 0"))
    assert(err("fp32:mhz=fast").contains("option mhz needs a clock above 0"))
    assert(err("fp32:family=virtex").contains("FPGA family 'virtex': expected one of cyclonev, arriav, ecp5"))
  }

  it should "reject bad names and options with messages that name them" in {
    def err(s: String) = ScpuConfig.parse(s).swap.getOrElse(fail(s"'$s' parsed"))
    assert(err("fp8").contains("unknown preset 'fp8'"))
    assert(err("fp32:foo=1").contains("unknown option 'foo'"))
    assert(err("fp32:add=x").contains("add needs an integer"))
    assert(err("fp32:add=-1").contains("addLatency must be >= 0"))
    assert(err("fp32:rm=up").contains("rounding mode 'up'"))
    assert(err("fp32:format=e12m60").contains("does not fit IEEE binary64"))
    assert(err("fp32:sqrt").contains("not key=value"))
  }

  it should "refuse configurations that cannot be built, saying why" in {
    val e1 = intercept[IllegalArgumentException](ScpuConfig(tagBits = 0))
    assert(e1.getMessage.contains("tagBits must be 1..64"))
    val e2 = intercept[IllegalArgumentException](ScpuConfig(format = FloatFormat(15, 20)))
    assert(e2.getMessage.contains("does not fit IEEE binary64"))
    val e3 = intercept[IllegalArgumentException](ScpuConfig(sqrtLatency = Some(-2)))
    assert(e3.getMessage.contains("sqrtLatency must be >= 0"))
    val e4 = intercept[IllegalArgumentException](ScpuConfig(addLatency = 0, mulLatency = 0, cmpLatency = 0,
      sqrtLatency = Some(0), recipLatency = Some(0)))
    assert(e4.getMessage.contains("total latency must be >= 1"))
  }
}
