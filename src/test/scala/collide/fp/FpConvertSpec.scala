package collide.fp

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.model.{FpConvertModel, FpResult}
import collide.testutil.{FpOracle, FpPatterns, PipeDriver, Seeds}

class FpConvertSpec extends AnyFlatSpec with ChiselScalatestTester {
  import FloatFormat._

  private def snan(f: FloatFormat, v: BigInt) =
    ((v >> f.fracBits) & f.expMask) == f.expMask && (v & f.fracMask) != 0 && !v.testBit(f.fracBits - 1)

  /** Independent oracle: exact BigDecimal value in `from`, rounded to `to` by FpOracle. */
  private def oracle(from: FpParams, to: FpParams, a: BigInt, rm: RoundingMode): FpResult = {
    val (bits, flags) = FpOracle.roundValue(to.format, FpOracle.decode(from.format, a, daz = !from.subnormals), rm, ftz = !to.subnormals)
    FpResult(bits, flags | (if (snan(from.format, a)) FpFlags.Invalid else 0))
  }

  behavior of "FpConvertModel"

  // Exact widening, checked through JVM Float (bf16 by shifting into binary32's top half,
  // fp16 by its exact decimal value) and then Float -> Double for fp64.
  for (from <- Seq(fp16, bf16); to <- Seq(fp32, fp64)) {
    it should s"widen every ${from.name} pattern exactly to ${to.name} in every rounding mode" in {
      val fp = FpParams(from); val tp = FpParams(to)
      for (a <- 0 until (1 << 16)) {
        val x: Float = if (from == bf16) java.lang.Float.intBitsToFloat(a << 16) else FpOracle.toFloat(fp16, BigInt(a))
        val want =
          if (to == fp32) BigInt(java.lang.Float.floatToRawIntBits(x)) & 0xffffffffL
          else BigInt(java.lang.Double.doubleToRawLongBits(x.toDouble)) & ((BigInt(1) << 64) - 1)
        val wantFlags = if (snan(from, BigInt(a))) FpFlags.Invalid else 0
        val rm = RoundingMode.all(a % 5)
        val got = FpConvertModel(fp, tp, BigInt(a), rm)
        if (x.isNaN) assert(got == FpResult(to.canonicalNaN, wantFlags), s"0x${a.toHexString}: got ${got.show(to)}")
        else assert(got == FpResult(want, 0), s"0x${a.toHexString} $rm: got ${got.show(to)}, want 0x${want.toString(16)}")
      }
    }
  }

  for ((from, to) <- Seq(fp16 -> bf16, bf16 -> fp16)) {
    it should s"convert every ${from.name} pattern to ${to.name} as exact BigDecimal rounding does, flags included" in {
      val fp = FpParams(from); val tp = FpParams(to)
      for (a <- 0 until (1 << 16); rm <- Seq(RoundingMode.RNE, RoundingMode.all(1 + a % 4))) {
        val want = oracle(fp, tp, BigInt(a), rm); val got = FpConvertModel(fp, tp, BigInt(a), rm)
        assert(got == want, s"0x${a.toHexString} $rm: got ${got.show(to)}, want ${want.show(to)}")
      }
    }
  }

  it should "narrow fp64 to fp32 as the JVM's double-to-float conversion does" in {
    val rng = Seeds.rng("FpConvertSpec-jvm-fp64-fp32")
    val ops = FpPatterns.specials(fp64) ++ FpPatterns.operands(fp64, rng, Seeds.cases(100000)) ++
      Seq.fill(Seeds.cases(20000))(BigInt(64, rng.self))
    for ((a, i) <- ops.zipWithIndex) {
      val x = java.lang.Double.longBitsToDouble(a.toLong).toFloat
      val got = FpConvertModel(FpParams.fp64, FpParams.fp32, a, RoundingMode.RNE).bits
      val want = BigInt(java.lang.Float.floatToRawIntBits(x)) & 0xffffffffL
      assert(got == want || (x.isNaN && got == fp32.canonicalNaN), s"case $i: 0x${a.toString(16)}: got 0x${got.toString(16)}, want 0x${want.toString(16)}")
    }
  }

  // Narrowing fp32 (and fp64) to the small formats, every mode, subnormals kept and flushed.
  for ((from, to) <- Seq(fp32 -> fp16, fp32 -> bf16, fp32 -> fp24, fp64 -> fp16, fp16 -> FloatFormat(3, 3),
                         FloatFormat(6, 12) -> bf16, FloatFormat(3, 3) -> FloatFormat(6, 12)); ftz <- Seq(false, true)) {
    val fp = FpParams(from, !ftz); val tp = FpParams(to, !ftz)
    val n = if (from == fp32 && !ftz && to != fp24) 100000 else 10000
    it should s"narrow ${fp.name} to ${tp.name} as exact BigDecimal rounding does in every mode, flags included" in {
      val rng = Seeds.rng(s"FpConvertSpec-exact-${fp.name}-${tp.name}")
      // Besides patterns of the source format, values near the target's rounding boundaries:
      // target patterns widened, with random bits below the target's last place.
      val near = FpPatterns.operands(to, rng, n / 4).map { t =>
        val v = FpConvertModel(FpParams(to), FpParams(from), t, RoundingMode.RNE).bits
        val extra = (from.sigBits - to.sigBits).max(0)
        if (((v >> from.fracBits) & from.expMask) == from.expMask || extra == 0) v else v ^ BigInt(extra, rng.self)
      }
      val ops = FpPatterns.specials(from) ++ near ++ FpPatterns.operands(from, rng, n / 2) ++ Seq.fill(n / 4)(BigInt(from.width, rng.self))
      for ((a, i) <- ops.zipWithIndex) {
        val rm = RoundingMode.all(rng.nextInt(5))
        val want = oracle(fp, tp, a, rm); val got = FpConvertModel(fp, tp, a, rm)
        assert(got == want, s"case $i: 0x${a.toString(16)} $rm: got ${got.show(to)}, want ${want.show(to)}")
      }
    }
  }

  it should "convert fp32 to fp16 in RNE as the JVM's float-to-double-to-fp16 rounding via BigDecimal" in {
    // A second route for the commonest narrowing: the float's exact double value rounded by FpOracle.fromDouble.
    val rng = Seeds.rng("FpConvertSpec-float-fp16")
    for (i <- 0 until Seeds.cases(20000)) {
      val a = BigInt(32, rng.self)
      val x = java.lang.Float.intBitsToFloat(a.toInt)
      val got = FpConvertModel(FpParams.fp32, FpParams(fp16), a, RoundingMode.RNE).bits
      val want = FpOracle.fromDouble(fp16, x.toDouble)
      assert(got == want, s"case $i: $x: got 0x${got.toString(16)}, want 0x${want.toString(16)}")
    }
  }

  behavior of "FpConvert"

  it should "emit SystemVerilog named after its parameters (FpConvert_fp32_to_fp16_ftz_L1)" in {
    val sv = circt.stage.ChiselStage.emitSystemVerilog(new FpConvert(FpParams.fp32, FpParams(fp16, subnormals = false), 1))
    assert(sv.contains("module FpConvert_fp32_to_fp16_ftz_L1("), sv.take(400))
  }

  val rtlConfigs: Seq[(FpParams, FpParams, Int)] = {
    val F = FpParams(_: FloatFormat); val Z = FpParams(_: FloatFormat, false)
    Seq(
      (F(fp32), F(fp16), 0), (F(fp16), F(fp32), 2), (Z(fp32), Z(fp16), 1), (F(fp16), Z(fp32), 0),
      (F(fp32), F(bf16), 2), (F(bf16), F(fp32), 0), (F(fp32), Z(bf16), 0),
      (F(fp64), F(fp32), 1), (F(fp32), F(fp64), 0), (Z(fp64), Z(fp32), 0),
      (F(fp16), F(bf16), 0), (F(bf16), F(fp16), 2), (Z(bf16), Z(fp16), 0),
      (F(fp24), F(fp32), 0), (F(fp32), F(fp24), 1), (F(fp64), F(fp16), 0), (F(fp16), F(fp64), 1),
      (F(fp32), F(fp32), 0), (F(fp32), Z(fp32), 1),
      (F(FloatFormat(3, 3)), F(fp16), 0), (F(fp16), F(FloatFormat(3, 3)), 1), (F(FloatFormat(6, 12)), Z(bf16), 0),
      // every stage registered (FpConvert.stages), and past it
      (F(fp32), F(fp24), 5), (F(fp64), Z(fp16), 5), (Z(fp32), F(fp16), 7)
    )
  }

  for ((from, to, lat) <- rtlConfigs) {
    it should s"match the golden model from ${from.name} to ${to.name} at latency $lat in every rounding mode${if (lat > 0) ", stalls included" else ""}" in {
      val rng = Seeds.rng(s"FpConvertSpec-rtl-${from.name}-${to.name}-L$lat")
      val n = Seeds.cases(1000)
      val ops = FpPatterns.operands(from.format, rng, n - n / 4) ++ Seq.fill(n / 4)(BigInt(from.width, rng.self))
      val vecs = ops.map(a => (a, RoundingMode.all(rng.nextInt(5))))
      val want = vecs.map { case (a, rm) => FpConvertModel(from, to, a, rm) }
      test(new FpConvert(from, to, lat)) { c =>
        PipeDriver.run(lat, vecs.size, rng, stalls = lat > 0)(
          en => c.io.en.poke(en.B),
          {
            case Some(i) => c.io.in.valid.poke(true.B); c.io.in.bits.a.poke(vecs(i)._1.U); c.io.in.bits.rm.poke(vecs(i)._2.hw)
            case None    => c.io.in.valid.poke(false.B)
          },
          () => c.io.out.valid.peek().litToBoolean,
          i => {
            val got = FpResult(c.io.out.bits.bits.peek().litValue, c.io.out.bits.flags.peek().litValue.toInt)
            assert(got == want(i), s"vector $i: 0x${vecs(i)._1.toString(16)} ${vecs(i)._2}: got ${got.show(to.format)}, want ${want(i).show(to.format)}")
          },
          () => c.clock.step()
        )
      }
    }
  }
}
