package collide.fp

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.model.{CompareResult, FpCompareModel}
import collide.testutil.{FpOracle, FpPatterns, PipeDriver, Seeds}

class FpCompareSpec extends AnyFlatSpec with ChiselScalatestTester {
  import FloatFormat._

  private def allPairs(f: FloatFormat) = { val s = FpPatterns.specials(f); for (a <- s; b <- s) yield (a, b) }
  /** Corners, pattern pairs (half with equal or adjacent magnitudes), random bits. */
  private def operandPairs(f: FloatFormat, rng: scala.util.Random, n: Int) =
    allPairs(f) ++ FpPatterns.pairs(f, rng, n / 4) ++
      FpPatterns.operands(f, rng, n / 4).flatMap { a =>
        val d = BigInt(rng.nextInt(3) - 1)
        Seq((a, (a + d).max(0).min(f.signBit * 2 - 1)), (a, a ^ f.signBit)) // neighbours and negation
      } ++ Seq.fill(n / 4)((BigInt(f.width, rng.self), BigInt(f.width, rng.self)))

  /** Independent oracle: JVM double comparison of exactly converted operands (fp32 through
    * Float itself), subnormals flushed first when p flushes. min/max by java.lang.Double.compare,
    * which orders -0 below +0. */
  private def oracle(p: FpParams, a: BigInt, b: BigInt): CompareResult = {
    val f = p.format
    def flush(x: BigInt) = if (!p.subnormals && ((x >> f.fracBits) & f.expMask) == 0) x & f.signBit else x
    val (fa, fb) = (flush(a), flush(b))
    def d(x: BigInt): Double =
      if (f == fp32) java.lang.Float.intBitsToFloat(x.toInt).toDouble
      else if (f == fp64) java.lang.Double.longBitsToDouble(x.toLong)
      else FpOracle.toDouble(f, x)
    val (x, y) = (d(fa), d(fb))
    def snan(v: BigInt) = ((v >> f.fracBits) & f.expMask) == f.expMask && (v & f.fracMask) != 0 && !v.testBit(f.fracBits - 1)
    val flags = if (snan(a) || snan(b)) FpFlags.Invalid else 0
    val (mn, mx) =
      if (x.isNaN && y.isNaN) (f.canonicalNaN, f.canonicalNaN)
      else if (x.isNaN) (fb, fb) else if (y.isNaN) (fa, fa)
      else if (java.lang.Double.compare(x, y) < 0) (fa, fb) else (fb, fa)
    CompareResult(x < y, x == y, x > y, x.isNaN || y.isNaN, flags, mn, mx)
  }

  behavior of "FpCompareModel"

  for (f <- FloatFormat.presets.map(_._2) ++ Seq(FloatFormat(3, 3), FloatFormat(6, 12)); sub <- Seq(true, false)) {
    val p = FpParams(f, sub)
    val n = if ((f == fp32 || f == fp64) && sub) 100000 else 20000
    it should s"agree with JVM comparison of exactly converted operands for ${p.name}, min and max included" in {
      val rng = Seeds.rng(s"FpCompareSpec-jvm-${p.name}")
      for (((a, b), i) <- operandPairs(f, rng, Seeds.cases(n)).zipWithIndex) {
        val want = oracle(p, a, b); val got = FpCompareModel(p, a, b)
        assert(got == want, s"case $i: 0x${a.toString(16)} vs 0x${b.toString(16)}: got ${got.show}, want ${want.show}")
      }
    }
  }

  it should "treat -0 and +0 as equal and order them -0 first in min and max" in {
    val p = FpParams(fp32)
    val r = FpCompareModel(p, fp32.zero(true), fp32.zero(false))
    assert(r.eq && !r.lt && !r.gt && r.min == fp32.zero(true) && r.max == fp32.zero(false) && r.flags == 0)
  }

  it should "raise invalid only for signaling NaN operands" in {
    val p = FpParams(fp16)
    val q = fp16.canonicalNaN; val s = fp16.infinity(false) | 1
    assert(FpCompareModel(p, q, BigInt(0)).flags == 0 && FpCompareModel(p, q, BigInt(0)).unordered)
    assert(FpCompareModel(p, BigInt(0x3c00), s).flags == FpFlags.Invalid)
  }

  behavior of "FpCompare"

  it should "emit SystemVerilog named after its parameters (FpCompare_fp64_L1)" in {
    val sv = circt.stage.ChiselStage.emitSystemVerilog(new FpCompare(FpParams.fp64, 1))
    assert(sv.contains("module FpCompare_fp64_L1("), sv.take(400))
  }

  val rtlConfigs: Seq[(FpParams, Int)] = FloatFormat.presets.map(_._2).zipWithIndex.flatMap { case (f, i) =>
    Seq((FpParams(f), if (i % 2 == 0) 0 else 2), (FpParams(f, subnormals = false), if (i % 2 == 0) 1 else 0))
  } ++ Seq((FpParams(FloatFormat(3, 3)), 1))

  for ((p, lat) <- rtlConfigs) {
    it should s"match the golden model for ${p.name} at latency $lat${if (lat > 0) ", stalls included" else ""}" in {
      val f = p.format
      val rng = Seeds.rng(s"FpCompareSpec-rtl-${p.name}-L$lat")
      val vecs = operandPairs(f, rng, Seeds.cases(1200)).drop(allPairs(f).size / 2)
      val want = vecs.map { case (a, b) => FpCompareModel(p, a, b) }
      test(new FpCompare(p, lat)) { c =>
        PipeDriver.run(lat, vecs.size, rng, stalls = lat > 0)(
          en => c.io.en.poke(en.B),
          {
            case Some(i) => c.io.in.valid.poke(true.B); c.io.in.bits.a.poke(vecs(i)._1.U); c.io.in.bits.b.poke(vecs(i)._2.U)
            case None    => c.io.in.valid.poke(false.B)
          },
          () => c.io.out.valid.peek().litToBoolean,
          i => {
            val o = c.io.out.bits
            val got = CompareResult(o.lt.peek().litToBoolean, o.eq.peek().litToBoolean, o.gt.peek().litToBoolean,
              o.unordered.peek().litToBoolean, o.flags.peek().litValue.toInt, o.min.peek().litValue, o.max.peek().litValue)
            assert(got == want(i), s"vector $i: 0x${vecs(i)._1.toString(16)} vs 0x${vecs(i)._2.toString(16)}: got ${got.show}, want ${want(i).show}")
          },
          () => c.clock.step()
        )
      }
    }
  }
}
