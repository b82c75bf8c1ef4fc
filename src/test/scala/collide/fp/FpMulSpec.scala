package collide.fp

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.model.{FpMulModel, FpResult}
import collide.testutil.{FpOracle, FpPatterns, PipeDriver, Seeds}

class FpMulSpec extends AnyFlatSpec with ChiselScalatestTester {
  import FloatFormat._

  private def sp(f: FloatFormat) = FpPatterns.specials(f)
  private def allPairs(f: FloatFormat) = for (a <- sp(f); b <- sp(f)) yield (a, b)
  /** Products that land near the subnormal range and overflow: exponents summing to about
    * -bias or +bias, so underflow, gradual underflow and overflow boundaries are hit. */
  private def edgePairs(f: FloatFormat, rng: scala.util.Random, n: Int) = Seq.fill(n) {
    val ea = 1 + rng.nextInt(f.expMask.toInt - 1)
    val target = if (rng.nextBoolean()) f.bias - f.sigBits - 1 + rng.nextInt(f.sigBits + 3) // tiny products
                 else 2 * f.bias + rng.nextInt(3) - 1                                        // near overflow
    val eb = (target - ea + f.bias).max(0).min(f.expMask.toInt - 1)
    def frac = BigInt(f.fracBits, rng.self)
    def sgn = if (rng.nextBoolean()) f.signBit else BigInt(0)
    (sgn | (BigInt(ea) << f.fracBits) | frac, sgn | (BigInt(eb) << f.fracBits) | frac)
  }
  private def operandPairs(f: FloatFormat, rng: scala.util.Random, n: Int) =
    allPairs(f) ++ edgePairs(f, rng, n / 4) ++ FpPatterns.operands(f, rng, n / 2).zip(FpPatterns.operands(f, rng, n / 2)) ++
      Seq.fill(n - n / 2 - n / 4)((BigInt(f.width, rng.self), BigInt(f.width, rng.self)))

  private def sameResult(f: FloatFormat, got: BigInt, want: BigInt) =
    got == want || (FpOracle.isNaN(f, got) && FpOracle.isNaN(f, want))

  behavior of "FpMulModel"

  it should "match JVM float multiplication for fp32 in RNE" in {
    val rng = Seeds.rng("FpMulSpec-jvm-fp32")
    val p = FpParams(fp32)
    for (((a, b), i) <- operandPairs(fp32, rng, Seeds.cases(100000)).zipWithIndex) {
      val x = java.lang.Float.intBitsToFloat(a.toInt); val y = java.lang.Float.intBitsToFloat(b.toInt)
      val want = BigInt(java.lang.Float.floatToRawIntBits(x * y)) & 0xffffffffL
      val got = FpMulModel(p, a, b, RoundingMode.RNE).bits
      assert(sameResult(fp32, got, want), s"case $i: $x * $y: got 0x${got.toString(16)}, want 0x${want.toString(16)}")
    }
  }

  it should "match JVM double multiplication for fp64 in RNE" in {
    val rng = Seeds.rng("FpMulSpec-jvm-fp64")
    val p = FpParams(fp64)
    val mask = (BigInt(1) << 64) - 1
    for (((a, b), i) <- operandPairs(fp64, rng, Seeds.cases(100000)).zipWithIndex) {
      val x = java.lang.Double.longBitsToDouble(a.toLong); val y = java.lang.Double.longBitsToDouble(b.toLong)
      val want = BigInt(java.lang.Double.doubleToRawLongBits(x * y)) & mask
      val got = FpMulModel(p, a, b, RoundingMode.RNE).bits
      assert(sameResult(fp64, got, want), s"case $i: $x * $y: got 0x${got.toString(16)}, want 0x${want.toString(16)}")
    }
  }

  // 2p+2 rule: fp16 and bf16 through float; fp24 (p=16 needs 34 bits) through double.
  for (f <- Seq(fp16, bf16, fp24)) {
    it should s"match JVM arithmetic rounded to ${f.name} (2p+2 rule) in RNE" in {
      val rng = Seeds.rng(s"FpMulSpec-2p2-${f.name}")
      val p = FpParams(f)
      val viaFloat = 2 * f.sigBits + 2 <= 24
      for (((a, b), i) <- operandPairs(f, rng, Seeds.cases(30000)).zipWithIndex) {
        val wide: Double =
          if (viaFloat) (FpOracle.toFloat(f, a) * FpOracle.toFloat(f, b)).toDouble
          else FpOracle.toDouble(f, a) * FpOracle.toDouble(f, b)
        val want = FpOracle.fromDouble(f, wide)
        val got = FpMulModel(p, a, b, RoundingMode.RNE).bits
        assert(sameResult(f, got, want), s"case $i: 0x${a.toString(16)} * 0x${b.toString(16)}: got 0x${got.toString(16)}, want 0x${want.toString(16)}")
      }
    }
  }

  /** Exact BigDecimal reference with IEEE's special cases, written apart from the model. */
  private def oracle(p: FpParams, a: BigInt, b: BigInt, rm: RoundingMode): (BigInt, Int) = {
    import FpOracle._
    val f = p.format
    val x = decode(f, a, daz = !p.subnormals)
    val y = decode(f, b, daz = !p.subnormals)
    val nv = if (Seq(x, y).contains(NaN(true))) FpFlags.Invalid else 0
    (x, y) match {
      case (NaN(_), _) | (_, NaN(_)) => (f.canonicalNaN, nv)
      case (Inf(_), n: Num) if n.isZero => (f.canonicalNaN, FpFlags.Invalid)
      case (n: Num, Inf(_)) if n.isZero => (f.canonicalNaN, FpFlags.Invalid)
      case (Inf(s), Inf(t)) => roundValue(f, Inf(s ^ t), rm)
      case (Inf(s), Num(t, _)) => roundValue(f, Inf(s ^ t), rm)
      case (Num(s, _), Inf(t)) => roundValue(f, Inf(s ^ t), rm)
      case (u: Num, v: Num) => round(f, u.signed.multiply(v.signed, U), rm, ftz = !p.subnormals, negZero = u.negative ^ v.negative)
      case _ => sys.error("unreachable")
    }
  }

  for (f <- FloatFormat.presets.map(_._2) ++ Seq(FloatFormat(3, 3), FloatFormat(6, 12)); sub <- Seq(true, false)) {
    val p = FpParams(f, sub)
    it should s"match exact BigDecimal arithmetic for ${p.name} in every rounding mode, flags included" in {
      val rng = Seeds.rng(s"FpMulSpec-exact-${p.name}")
      val n = Seeds.cases(if (f == fp64) 4000 else 6000)
      val corner = allPairs(f).flatMap { case (a, b) => RoundingMode.all.map(rm => (a, b, rm)) }
      val random = operandPairs(f, rng, n).drop(allPairs(f).size).map { case (a, b) => (a, b, RoundingMode.all(rng.nextInt(5))) }
      for (((a, b, rm), i) <- (corner ++ random).zipWithIndex) {
        val (wb, wf) = oracle(p, a, b, rm)
        val got = FpMulModel(p, a, b, rm)
        assert(got == FpResult(wb, wf), s"case $i: 0x${a.toString(16)} * 0x${b.toString(16)} $rm: got ${got.show(f)}, want ${FpResult(wb, wf).show(f)}")
      }
    }
  }

  it should "match exact BigDecimal arithmetic on every e3m3 operand pair, every mode and subnormal setting" in {
    val f = FloatFormat(3, 3)
    for (sub <- Seq(true, false); a <- 0 until 64; b <- 0 until 64; rm <- RoundingMode.all) {
      val p = FpParams(f, sub)
      val want = oracle(p, BigInt(a), BigInt(b), rm); val got = FpMulModel(p, BigInt(a), BigInt(b), rm)
      assert(got == FpResult(want._1, want._2), s"${p.name} 0x${a.toHexString} * 0x${b.toHexString} $rm: got ${got.show(f)}, want ${FpResult(want._1, want._2).show(f)}")
    }
  }

  behavior of "FpMul"

  it should "emit SystemVerilog named after its parameters (FpMul_bf16_L3)" in {
    val sv = circt.stage.ChiselStage.emitSystemVerilog(new FpMul(FpParams(bf16), 3))
    assert(sv.contains("module FpMul_bf16_L3("), sv.take(400))
  }

  // The preset formats at latencies 0 and 3, a few more, and every stage registered: on the
  // default family (27-bit tiles: one for fp32, four for fp64, two adder levels) and on ECP5
  // (18-bit tiles: four for fp32, nine for fp64).
  val rtlConfigs: Seq[(FpParams, Int, FpgaFamily)] = collide.testutil.FpRtlMatrix.configs(
    (FpParams(fp32), 1), (FpParams(bf16), 2), (FpParams(FloatFormat(3, 3)), 0), (FpParams(FloatFormat(10, 40), false), 2),
    (FpParams(fp32), 8), (FpParams(fp64), 10), (FpParams(fp16, false), 4)).map { case (p, l) => (p, l, FpgaFamily.default) } ++
    Seq((FpParams(fp32), 10, FpgaFamily.ecp5), (FpParams(fp64), 12, FpgaFamily.ecp5), (FpParams(fp24), 3, FpgaFamily.ecp5))

  it should "cut its significands into the family's DSP tiles and sum them in a tree of one level a stage" in {
    assert(FpMul.chunks(24, 27) == Seq((0, 24)) && FpMul.treeLevels(24, 27) == 0)
    assert(FpMul.chunks(53, 27) == Seq((0, 27), (27, 26)) && FpMul.treeLevels(53, 27) == 2)
    assert(FpMul.chunks(24, 18) == Seq((0, 18), (18, 6)) && FpMul.treeLevels(24, 18) == 2)
    assert(FpMul.chunks(53, 18).size == 3 && FpMul.treeLevels(53, 18) == 4)
    assert(FpMul.delays(FpParams(fp64), FpgaFamily.default).size == 10)
  }

  for ((p, lat, fam) <- rtlConfigs) {
    val on = if (fam == FpgaFamily.default) "" else s" placed for ${fam.name}"
    it should s"match the golden model for ${p.name} at latency $lat$on in every rounding mode${if (lat > 0) ", stalls included" else ""}" in {
      val f = p.format
      val rng = Seeds.rng(s"FpMulSpec-rtl-${p.name}-L$lat-${fam.name}")
      val n = Seeds.cases(if (f.width > 32) 600 else 1200)
      val vecs = (edgePairs(f, rng, n / 4) ++ FpPatterns.operands(f, rng, n / 2).zip(FpPatterns.operands(f, rng, n / 2)) ++
        Seq.fill(n / 4)((BigInt(f.width, rng.self), BigInt(f.width, rng.self))))
        .map { case (a, b) => (a, b, RoundingMode.all(rng.nextInt(5))) }
      val want = vecs.map { case (a, b, rm) => FpMulModel(p, a, b, rm) }
      test(new FpMul(p, lat, fam)) { c =>
        PipeDriver.run(lat, vecs.size, rng, stalls = lat > 0)(
          en => c.io.en.poke(en.B),
          {
            case Some(i) =>
              val (a, b, rm) = vecs(i)
              c.io.in.valid.poke(true.B); c.io.in.bits.a.poke(a.U); c.io.in.bits.b.poke(b.U); c.io.in.bits.rm.poke(rm.hw)
            case None => c.io.in.valid.poke(false.B)
          },
          () => c.io.out.valid.peek().litToBoolean,
          i => {
            val got = FpResult(c.io.out.bits.bits.peek().litValue, c.io.out.bits.flags.peek().litValue.toInt)
            val (a, b, rm) = vecs(i)
            assert(got == want(i), s"vector $i: 0x${a.toString(16)} * 0x${b.toString(16)} $rm: got ${got.show(f)}, want ${want(i).show(f)}")
          },
          () => c.clock.step()
        )
      }
    }
  }
}
