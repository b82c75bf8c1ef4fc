package collide.world

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.scpu.ScpuConfig
import collide.testutil.{FpPatterns, Seeds}
import collide.world.BroadPhaseWorlds._
import collide.world.model.{BroadPhaseModel, WorldSphere}

class CellExponentSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "CellExponent"

  /** Worlds of the broad-phase specs plus worlds of raw bit patterns (NaNs, infinities,
    * subnormals, negative radii), each streamed after a clear. */
  private def worlds(cfg: ScpuConfig, rng: scala.util.Random): Seq[(String, IndexedSeq[WorldSphere])] = {
    val f = cfg.linkFormat
    val shaped = Seq("empty" -> Seq.empty[S], "one" -> Seq(S(1, 2, 3, 0.5)), "uniform" -> uniform(rng, 60),
      "radii 1:1000" -> mixedRadii(rng, 50), "huge" -> huge(rng, 30, 5), "one point" -> onePoint(20),
      "tiny separations" -> tinySeparations, "negative" -> uniform(rng, 40, origin = -1000.0))
      .map { case (l, w) => l -> bits(f, w) }
    val raw = Seq.tabulate(Seeds.cases(12)) { i =>
      s"raw patterns $i" -> IndexedSeq.fill(1 + rng.nextInt(40)) {
        val v = FpPatterns.operands(f, rng, 4)
        WorldSphere(v(0), v(1), v(2), v(3))
      }
    }
    shaped ++ raw
  }

  for (cfg <- Seq(ScpuConfig.fp32, ScpuConfig.fp16);
       bp <- Seq(BroadPhaseParams.default, BroadPhaseParams.default.copy(largeMax = 2), BroadPhaseParams.default.copy(cellSteps = 2));
       ports <- Seq(1, 2)) {
    it should s"choose the golden model's cell level for ${cfg.name} worlds with largeMax ${bp.largeMax}, ${bp.cellSteps} cell step(s) an octave, $ports sphere(s) a cycle" in {
      val model = new BroadPhaseModel(cfg, bp)
      val rng = Seeds.rng(s"CellExponentSpec-${cfg.name}-${bp.largeMax}-e${bp.cellSteps}-p$ports")
      val p = cfg.params
      test(new CellExponent(p, bp, ports)) { dut =>
        def idle(): Unit = dut.io.in.foreach(_.valid.poke(false.B))
        for ((label, w) <- worlds(cfg, rng)) {
          dut.io.clear.poke(true.B); idle(); dut.clock.step(); dut.io.clear.poke(false.B)
          // With two ports, a port sometimes idles, so spheres meet both ports in any order.
          var rest = w
          while (rest.nonEmpty) {
            idle()
            for (port <- dut.io.in if rest.nonEmpty && (ports == 1 || rng.nextInt(4) != 0)) {
              val s = rest.head; rest = rest.tail
              val c = model.converted(s)
              val excluded = model.excluded(s)
              port.valid.poke(true.B)
              port.nonFinite.poke(excluded.B)
              if (!excluded) {
                val need = model.need(c(3))
                port.needNone.poke((need == Int.MinValue).B)
                port.need.poke((if (need == Int.MinValue) 0 else need).S)
                val tops = c.take(3).flatMap(model.topExp).filter(_ != Int.MinValue)
                port.topNone.poke(tops.isEmpty.B)
                port.top.poke((if (tops.isEmpty) 0 else tops.max).S)
              }
            }
            dut.clock.step()
          }
          idle()
          dut.clock.step(CellExponent.levelLatency)
          val eligible = w.filterNot(model.excluded).map(model.converted)
          val want = model.chooseLevel(eligible)
          assert(dut.io.level.peek().litValue == want, s"${cfg.name} $label (${w.length} spheres, ${eligible.length} eligible)")
        }
      }
    }
  }
}
