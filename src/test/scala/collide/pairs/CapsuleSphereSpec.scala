package collide.pairs

import scala.util.Random
import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.pairs.model._
import collide.scpu.ScpuConfig
import collide.scpu.model.ScpuResult
import collide.testutil.{Builds, Seeds, Slow}

/** The CapsuleSphere unit against CapsuleSphereModel, bit for bit (kind, every field, d, w,
  * flags, nonFinite, tag), on Verilator: the hard cases back to back (each result exactly
  * `latency` cycles on), then random pairs with input bubbles and stalls (io.en low). */
class CapsuleSphereSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "CapsuleSphere"

  private def run(cfg: ScpuConfig, n: Int): Unit = {
    val rng = Seeds.rng(s"CapsuleSphereSpec-${cfg.name}")
    val vec = new CapsuleSphereVectors(cfg)
    val labelled = vec.hardCases ++ Seq.tabulate(n)(i => s"random $i" -> vec.random(rng, if (i % 4 == 0) 1e3 else 10)) ++
      Seq.tabulate(n / 4)(i => s"raw $i" -> vec.raw(rng))
    val pairs = labelled.zipWithIndex.map { case ((_, p), i) => p.copy(tag = BigInt(i)) }
    val model = new CapsuleSphereModel(cfg)
    val expected = pairs.map(model.collide)
    test(new CapsuleSphere(cfg)).withAnnotations(Builds.verilator("CapsuleSphereSpec", cfg.id)) { dut =>
      val lat = CapsuleSphere.latency(cfg)
      def poke(p: CapsuleSpherePair): Unit = {
        val i = dut.io.in.bits
        Seq(i.cx, i.cy, i.cz, i.ax, i.ay, i.az, i.lz, i.rc, i.sx, i.sy, i.sz, i.rs).zip(p.fields).foreach { case (port, v) => port.poke(v.U) }
        i.tag.poke(p.tag.U)
      }
      def check(k: Int): Unit = {
        val o = dut.io.out.bits
        val got = ScpuResult(o.hit.peek().litToBoolean, o.kind.peek().litValue.toInt, o.px.peek().litValue, o.py.peek().litValue,
          o.pz.peek().litValue, o.nx.peek().litValue, o.ny.peek().litValue, o.nz.peek().litValue, o.depth.peek().litValue,
          o.meta.nonFinite.peek().litToBoolean, o.meta.flags.peek().litValue.toInt, o.meta.tag.peek().litValue,
          o.d.peek().litValue, o.nw.peek().litValue)
        assert(got == expected(k), s"${cfg.name}, ${labelled(k)._1}: ${pairs(k)}\n  rtl   ${got.show}\n  model ${expected(k).show}")
      }
      PairUnitDriver.run(dut.clock, dut.io.en, dut.io.in.valid, dut.io.out.valid, lat, vec.hardCases.size, pairs.size,
        new Random(rng.nextLong()), cfg.name)(k => poke(pairs(k)), () => dut.io.out.bits.meta.tag.peek().litValue.toInt, check)
      info(s"${cfg.name}: ${pairs.size} pairs (${vec.hardCases.size} hard cases), latency $lat, ${expected.count(_.hit)} contacts")
    }
  }

  it should "equal its golden model bit for bit in fp32 pipelined for 200 MHz, through stalls and bubbles" in {
    run(ScpuConfig.fp32At200, Seeds.cases(3000))
  }
  it should "equal its golden model bit for bit in fp16, where products overflow" in {
    run(ScpuConfig.fp16, Seeds.cases(3000))
  }
  it should "equal its golden model bit for bit in fp64" taggedAs (Slow) in {
    run(ScpuConfig.fp64, Seeds.cases(3000))
  }
}
