package collide.fp

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.model.{FpAddModel, FpResult}
import collide.testutil.{FpOracle, FpPatterns, PipeDriver, Seeds}

class FpAddSpec extends AnyFlatSpec with ChiselScalatestTester {
  import FloatFormat._

  private def sp(f: FloatFormat) = FpPatterns.specials(f)
  private def allPairs(f: FloatFormat) = for (a <- sp(f); b <- sp(f)) yield (a, b)
  /** Corner pairs, special x special, plus random patterns and random bits. */
  private def operandPairs(f: FloatFormat, rng: scala.util.Random, n: Int) =
    allPairs(f) ++ FpPatterns.pairs(f, rng, n / 2) ++ Seq.fill(n - n / 2)((BigInt(f.width, rng.self), BigInt(f.width, rng.self)))

  private def sameResult(f: FloatFormat, got: BigInt, want: BigInt) =
    got == want || (FpOracle.isNaN(f, got) && FpOracle.isNaN(f, want))

  behavior of "FpAddModel"

  it should "match JVM float addition and subtraction for fp32 in RNE" in {
    val rng = Seeds.rng("FpAddSpec-jvm-fp32")
    val p = FpParams(fp32)
    for (((a, b), i) <- operandPairs(fp32, rng, Seeds.cases(100000)).zipWithIndex; sub <- Seq(false, true)) {
      val x = java.lang.Float.intBitsToFloat(a.toInt); val y = java.lang.Float.intBitsToFloat(b.toInt)
      val want = BigInt(java.lang.Float.floatToRawIntBits(if (sub) x - y else x + y)) & 0xffffffffL
      val got = FpAddModel(p, a, b, RoundingMode.RNE, sub).bits
      assert(sameResult(fp32, got, want), f"case $i: $x%s ${if (sub) "-" else "+"} $y%s: got 0x${got.toString(16)}, want 0x${want.toString(16)}")
    }
  }

  it should "match JVM double addition and subtraction for fp64 in RNE" in {
    val rng = Seeds.rng("FpAddSpec-jvm-fp64")
    val p = FpParams(fp64)
    val mask = (BigInt(1) << 64) - 1
    for (((a, b), i) <- operandPairs(fp64, rng, Seeds.cases(100000)).zipWithIndex; sub <- Seq(false, true)) {
      val x = java.lang.Double.longBitsToDouble(a.toLong); val y = java.lang.Double.longBitsToDouble(b.toLong)
      val want = BigInt(java.lang.Double.doubleToRawLongBits(if (sub) x - y else x + y)) & mask
      val got = FpAddModel(p, a, b, RoundingMode.RNE, sub).bits
      assert(sameResult(fp64, got, want), f"case $i: $x%s ${if (sub) "-" else "+"} $y%s: got 0x${got.toString(16)}, want 0x${want.toString(16)}")
    }
  }

  // 2p+2 rule: fp16 (p=11) and bf16 (p=8) through float (p=24); fp24 (p=16) needs 34 bits: double.
  for (f <- Seq(fp16, bf16, fp24)) {
    it should s"match JVM arithmetic rounded to ${f.name} (2p+2 rule) in RNE" in {
      val rng = Seeds.rng(s"FpAddSpec-2p2-${f.name}")
      val p = FpParams(f)
      val viaFloat = 2 * f.sigBits + 2 <= 24
      for (((a, b), i) <- operandPairs(f, rng, Seeds.cases(30000)).zipWithIndex; sub <- Seq(false, true)) {
        val wide: Double =
          if (viaFloat) { val x = FpOracle.toFloat(f, a); val y = FpOracle.toFloat(f, b); (if (sub) x - y else x + y).toDouble }
          else { val x = FpOracle.toDouble(f, a); val y = FpOracle.toDouble(f, b); if (sub) x - y else x + y }
        val want = FpOracle.fromDouble(f, wide)
        val got = FpAddModel(p, a, b, RoundingMode.RNE, sub).bits
        assert(sameResult(f, got, want), s"case $i: 0x${a.toString(16)} ${if (sub) "-" else "+"} 0x${b.toString(16)}: got 0x${got.toString(16)}, want 0x${want.toString(16)}")
      }
    }
  }

  /** Exact BigDecimal reference with IEEE's special cases, written apart from the model. */
  private def oracle(p: FpParams, a: BigInt, b: BigInt, rm: RoundingMode, sub: Boolean): (BigInt, Int) = {
    import FpOracle._
    val f = p.format
    val x = decode(f, a, daz = !p.subnormals)
    val y = decode(f, b, daz = !p.subnormals) match {
      case Inf(n) => Inf(n ^ sub); case Num(n, v) => Num(n ^ sub, v); case o => o
    }
    val nv = if (Seq(x, y).contains(NaN(true))) FpFlags.Invalid else 0
    (x, y) match {
      case (NaN(_), _) | (_, NaN(_)) => (f.canonicalNaN, nv)
      case (Inf(s), Inf(t)) if s != t => (f.canonicalNaN, FpFlags.Invalid)
      case (Inf(s), _) => roundValue(f, Inf(s), rm)
      case (_, Inf(s)) => roundValue(f, Inf(s), rm)
      case (u: Num, v: Num) =>
        val s = u.signed.add(v.signed, U)
        val negZero = if (u.isZero && v.isZero && u.negative == v.negative) u.negative else rm == RoundingMode.RDN
        round(f, s, rm, ftz = !p.subnormals, negZero = negZero)
      case _ => sys.error("unreachable")
    }
  }

  for (f <- FloatFormat.presets.map(_._2) ++ Seq(FloatFormat(3, 3), FloatFormat(6, 12)); sub <- Seq(true, false)) {
    val p = FpParams(f, sub)
    it should s"match exact BigDecimal arithmetic for ${p.name} in every rounding mode, flags included" in {
      val rng = Seeds.rng(s"FpAddSpec-exact-${p.name}")
      val n = Seeds.cases(if (f == fp64) 4000 else 6000)
      val corner = allPairs(f).flatMap { case (a, b) => RoundingMode.all.map(rm => (a, b, rm)) }
      val random = FpPatterns.pairs(f, rng, n).map { case (a, b) => (a, b, RoundingMode.all(rng.nextInt(5))) }
      for (((a, b, rm), i) <- (corner ++ random).zipWithIndex) {
        val s = rng.nextBoolean()
        val (wb, wf) = oracle(p, a, b, rm, s)
        val got = FpAddModel(p, a, b, rm, s)
        assert(got == FpResult(wb, wf), s"case $i: 0x${a.toString(16)} ${if (s) "-" else "+"} 0x${b.toString(16)} $rm: got ${got.show(f)}, want ${FpResult(wb, wf).show(f)}")
      }
    }
  }

  it should "match exact BigDecimal arithmetic on every e3m3 operand pair, both signs of b, every mode and subnormal setting" in {
    val f = FloatFormat(3, 3)
    for (sub <- Seq(true, false); a <- 0 until 64; b <- 0 until 64; s <- Seq(false, true); rm <- RoundingMode.all) {
      val p = FpParams(f, sub)
      val want = oracle(p, BigInt(a), BigInt(b), rm, s); val got = FpAddModel(p, BigInt(a), BigInt(b), rm, s)
      assert(got == FpResult(want._1, want._2), s"${p.name} 0x${a.toHexString} ${if (s) "-" else "+"} 0x${b.toHexString} $rm: got ${got.show(f)}, want ${FpResult(want._1, want._2).show(f)}")
    }
  }

  behavior of "FpAdd"

  it should "emit SystemVerilog named after its parameters (FpAdd_fp32_ftz_L2)" in {
    val sv = circt.stage.ChiselStage.emitSystemVerilog(new FpAdd(FpParams(fp32, subnormals = false), 2))
    assert(sv.contains("module FpAdd_fp32_ftz_L2("), sv.take(400))
  }

  // The preset formats at latencies 0 and 3, a few more, and every stage registered (10): on
  // the default family and on ECP5, whose delays place the registers elsewhere.
  val rtlConfigs: Seq[(FpParams, Int, FpgaFamily)] = collide.testutil.FpRtlMatrix.configs(
    (FpParams(fp32), 1), (FpParams(fp16), 2), (FpParams(FloatFormat(3, 3)), 0), (FpParams(FloatFormat(10, 40), false), 2),
    (FpParams(fp32), 12), (FpParams(fp64), 12), (FpParams(fp16, false), 6)).map { case (p, l) => (p, l, FpgaFamily.default) } ++
    Seq((FpParams(fp32), 5, FpgaFamily.ecp5), (FpParams(bf16), 12, FpgaFamily.ecp5), (FpParams(fp32), 15, FpgaFamily.arriaV))

  it should "place one register at each of its twelve stage boundaries at latency 12, and stack the rest at the output" in {
    assert(Pipeline.balanced(12, FpAdd.delays(FpParams(fp32), FpgaFamily.default)) == Seq.fill(12)(1))
    assert(Pipeline.balanced(15, FpAdd.delays(FpParams(fp32), FpgaFamily.default)) == Seq.fill(11)(1) :+ 4)
  }

  for ((p, lat, fam) <- rtlConfigs) {
    val on = if (fam == FpgaFamily.default) "" else s" placed for ${fam.name}"
    it should s"match the golden model for ${p.name} at latency $lat$on in every rounding mode${if (lat > 0) ", stalls included" else ""}" in {
      val f = p.format
      val rng = Seeds.rng(s"FpAddSpec-rtl-${p.name}-L$lat-${fam.name}")
      val n = Seeds.cases(if (f.width > 32) 600 else 1200)
      val vecs = (FpPatterns.pairs(f, rng, n - n / 4) ++ Seq.fill(n / 4)((BigInt(f.width, rng.self), BigInt(f.width, rng.self))))
        .map { case (a, b) => (a, b, rng.nextBoolean(), RoundingMode.all(rng.nextInt(5))) }
      val want = vecs.map { case (a, b, s, rm) => FpAddModel(p, a, b, rm, s) }
      test(new FpAdd(p, lat, fam)) { c =>
        PipeDriver.run(lat, vecs.size, rng, stalls = lat > 0)(
          en => c.io.en.poke(en.B),
          {
            case Some(i) =>
              val (a, b, s, rm) = vecs(i)
              c.io.in.valid.poke(true.B); c.io.in.bits.a.poke(a.U); c.io.in.bits.b.poke(b.U)
              c.io.in.bits.subtract.poke(s.B); c.io.in.bits.rm.poke(rm.hw)
            case None => c.io.in.valid.poke(false.B)
          },
          () => c.io.out.valid.peek().litToBoolean,
          i => {
            val got = FpResult(c.io.out.bits.bits.peek().litValue, c.io.out.bits.flags.peek().litValue.toInt)
            val (a, b, s, rm) = vecs(i)
            assert(got == want(i), s"vector $i: 0x${a.toString(16)} ${if (s) "-" else "+"} 0x${b.toString(16)} $rm: got ${got.show(f)}, want ${want(i).show(f)}")
          },
          () => c.clock.step()
        )
      }
    }
  }
}
