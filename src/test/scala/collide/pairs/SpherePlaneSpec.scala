package collide.pairs

import scala.util.Random
import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.pairs.model._
import collide.scpu.ScpuConfig
import collide.testutil.{Builds, Seeds, Slow}

/** The SpherePlane unit against SpherePlaneModel, bit for bit (values, hit, flags, tag), on
  * Verilator: the hard cases back to back (one pair a cycle, each result `latency` cycles on),
  * then random pairs with input bubbles and stalls (io.en low). */
class SpherePlaneSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "SpherePlane"

  private def run(cfg: ScpuConfig, n: Int): Unit = {
    val rng = Seeds.rng(s"SpherePlaneSpec-${cfg.name}")
    val vec = new SpherePlaneVectors(cfg)
    val labelled = vec.hardCases ++ Seq.tabulate(n)(i => s"random $i" -> vec.random(rng, if (i % 4 == 0) 1e3 else 10)) ++
      Seq.tabulate(n / 4)(i => s"raw $i" -> vec.raw(rng))
    val pairs = labelled.zipWithIndex.map { case ((_, p), i) => p.copy(tag = BigInt(i)) }
    val model = new SpherePlaneModel(cfg)
    val expected = pairs.map(model.collide)
    test(new SpherePlane(cfg)).withAnnotations(Builds.verilator("SpherePlaneSpec", cfg.id)) { dut =>
      val lat = SpherePlane.latency(cfg)
      def poke(p: SpherePlanePair): Unit = {
        val i = dut.io.in.bits
        i.cx.poke(p.cx.U); i.cy.poke(p.cy.U); i.cz.poke(p.cz.U); i.r.poke(p.r.U)
        i.nx.poke(p.nx.U); i.ny.poke(p.ny.U); i.nz.poke(p.nz.U); i.d.poke(p.d.U); i.tag.poke(p.tag.U)
      }
      def check(k: Int): Unit = {
        val o = dut.io.out.bits
        val got = SpherePlaneResult(o.hit.peek().litToBoolean, o.px.peek().litValue, o.py.peek().litValue, o.pz.peek().litValue,
          o.nx.peek().litValue, o.ny.peek().litValue, o.nz.peek().litValue, o.depth.peek().litValue,
          o.nonFinite.peek().litToBoolean, o.flags.peek().litValue.toInt, o.tag.peek().litValue)
        assert(got == expected(k), s"${cfg.name}, ${labelled(k)._1}: ${pairs(k)}\n  rtl   $got\n  model ${expected(k)}")
      }
      PairUnitDriver.run(dut.clock, dut.io.en, dut.io.in.valid, dut.io.out.valid, lat, vec.hardCases.size, pairs.size,
        new Random(rng.nextLong()), cfg.name)(k => poke(pairs(k)), () => dut.io.out.bits.tag.peek().litValue.toInt, check)
      info(s"${cfg.name}: ${pairs.size} pairs (${vec.hardCases.size} hard cases), latency $lat, ${expected.count(_.hit)} contacts")
    }
  }

  it should "equal its golden model bit for bit in fp32 pipelined for 200 MHz, through stalls and bubbles" in {
    run(ScpuConfig.fp32At200, Seeds.cases(3000))
  }
  it should "equal its golden model bit for bit in fp16, where products and depths overflow" in {
    run(ScpuConfig.fp16, Seeds.cases(3000))
  }
  it should "equal its golden model bit for bit in fp64" taggedAs (Slow) in {
    run(ScpuConfig.fp64, Seeds.cases(3000))
  }
}
