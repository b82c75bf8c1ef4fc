package collide.fp

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.model.SoftFloat
import collide.testutil.Seeds

/** Exposes the combinational rounder for testing. */
class RoundRawHarness(val p: FpParams, val ew: Int) extends Module {
  val io = IO(new Bundle {
    val in  = Input(new RoundIn(p.format, ew))
    val rm  = Input(UInt(3.W))
    val out = Output(new FpOut(p.format.width))
  })
  io.out := RoundRaw(p, io.in, io.rm)
  override def desiredName = s"RoundRawHarness_${p.name}"
}

class RoundRawSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "RoundRaw"

  val configs = FloatFormat.presets.map(_._2).flatMap(f => Seq(FpParams(f), FpParams(f, subnormals = false)))

  for (p <- configs) {
    it should s"round exactly as SoftFloat.roundPack for ${p.name} in every mode" in {
      val f   = p.format
      val ew  = f.rawExpWidth + 2
      val rng = Seeds.rng(s"RoundRawSpec-${p.name}")
      test(new RoundRawHarness(p, ew)) { c =>
        c.io.in.isNaN.poke(false.B); c.io.in.isInf.poke(false.B); c.io.in.isZero.poke(false.B)
        c.io.in.flags.poke(0.U)
        val lo = f.minSubExp - 4; val hi = f.maxExp + 2
        val n = Seeds.cases(4000)
        for (i <- 0 until n) {
          // Exponents concentrated at the edges (subnormal boundary, overflow) and anywhere.
          val sExp = rng.nextInt(4) match {
            case 0 => f.minExp - rng.nextInt(f.sigBits + 4)
            case 1 => f.maxExp - 1 + rng.nextInt(3)
            case _ => lo + rng.nextInt(hi - lo + 1)
          }
          val body = BigInt(f.sigBits + 1, rng.self)
          // Low bits patterned to hit ties and carries often.
          val low = rng.nextInt(4) match {
            case 0 => body | ((BigInt(1) << (f.sigBits + 1)) - 1)
            case 1 => body & ~BigInt(3) | 2
            case _ => body
          }
          val sig  = (BigInt(1) << (f.sigBits + 1)) | (low & ((BigInt(1) << (f.sigBits + 1)) - 1))
          val sign = rng.nextBoolean()
          val rm   = RoundingMode.all(rng.nextInt(5))
          c.io.in.sign.poke(sign.B); c.io.in.sExp.poke(sExp.S); c.io.in.sig.poke(sig.U)
          c.io.rm.poke(rm.hw)
          val exp = SoftFloat.roundPack(p, sign, sig >> 1, sExp - f.sigBits, sig.testBit(0), rm)
          val gotBits = c.io.out.bits.peek().litValue
          val gotFlags = c.io.out.flags.peek().litValue.toInt
          assert(gotBits == exp.bits && gotFlags == exp.flags,
            s"case $i: sign=$sign sExp=$sExp sig=0x${sig.toString(16)} $rm: got 0x${gotBits.toString(16)} [${FpFlags.show(gotFlags)}], want ${exp.show(f)}")
        }
      }
    }
  }
}
