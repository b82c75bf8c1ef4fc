package collide.world

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.FloatFormat
import collide.fp.model.{Decoded, SoftFloat}
import collide.scpu.ScpuConfig
import collide.scpu.model.ScpuModel
import collide.testutil.{FpPatterns, Seeds}
import collide.world.model.BroadPhaseModel

class SphereKeysSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "SphereKeys"

  private val configs = Seq(ScpuConfig.fp32, ScpuConfig.fp32.copy(name = "fp32-ftz", subnormals = false),
    ScpuConfig.fp16, ScpuConfig.bf16, ScpuConfig.fp64)

  private def finite(cfg: ScpuConfig, b: BigInt) = SoftFloat.decode(cfg.params, b) match {
    case Decoded.NaN(_) | Decoded.Inf(_) => false
    case _                               => true
  }

  /** Values around cell faces and the pattern generator's corners (subnormals, extremes). */
  private def values(cfg: ScpuConfig, rng: scala.util.Random, n: Int): Seq[BigInt] = {
    val f = cfg.format
    val faces = Seq.fill(n / 4) {
      val v = (rng.nextInt(41) - 20) * math.pow(2, rng.nextInt(9) - 4)
      val b = ScpuModel.fromDouble(f, v)
      rng.nextInt(3) match { case 0 => b; case 1 => (b + 1).min(f.signBit * 2 - 1); case _ => (b - 1).max(0) }
    }
    FpPatterns.specials(f) ++ faces ++ FpPatterns.operands(f, rng, n)
  }

  /** A cell level that puts v's cell in range most of the time, and sometimes one that
    * overflows it; odd levels (edges of 1.5 * 2^k) only with two cell steps. */
  private def levelFor(cfg: ScpuConfig, bp: BroadPhaseParams, rng: scala.util.Random, v: BigInt): Int = {
    val k = SoftFloat.decode(cfg.params, v) match {
      case Decoded.Finite(_, sig, e) =>
        val top = e + sig.bitLength
        top - bp.cellBits + 2 + (if (rng.nextInt(8) == 0) -(1 + rng.nextInt(4)) else rng.nextInt(30))
      case _ => rng.nextInt(40) - 20
    }
    2 * k - (if (bp.cellSteps == 2) rng.nextInt(2) else 0)
  }

  for (cfg <- configs; steps <- Seq(1, 2)) {
    val edges = if (steps == 2) "edges 2^k and 1.5 * 2^k" else "edges 2^k alone"
    val bp = BroadPhaseParams.default.copy(cellSteps = steps)
    // Latency 1 (the output registered) and the 200 MHz latency (every segment its own stage),
    // a new sphere each cycle, so a value staged wrongly meets another sphere's.
    for (latency <- Seq(1, SphereKeys.latencyFor(cfg.params, bp, 200)).distinct)
    it should s"give the golden model's cells, box keys, needs and tops for ${cfg.name} values, faces and corners, $edges, at latency $latency" in {
      val model = new BroadPhaseModel(cfg, bp)
      val rng = Seeds.rng(s"SphereKeysSpec-${cfg.name}-e$steps")
      val vs = values(cfg, rng, Seeds.cases(600)).toIndexedSeq
      val qw = SphereKeys.qWidth(bp)
      val qrMax = (BigInt(1) << qw) - 1
      var inRange, overflowed, needs = 0
      val cases = vs.indices.map { idx =>
        val sphere = Seq(vs(idx), vs(rng.nextInt(vs.length)), vs(rng.nextInt(vs.length)), vs(rng.nextInt(vs.length)))
        (sphere, sphere.take(3).map(levelFor(cfg, bp, rng, _)).max)
      }
      test(new SphereKeys(cfg.params, bp, latency)) { dut =>
        def check(idx: Int): Unit = {
          val (sphere, level) = cases(idx)
          val r = sphere(3)
          val label = s"${cfg.name} case $idx: sphere ${sphere.map(b => "0x" + b.toString(16)).mkString(",")} level $level"
          assert(dut.io.out.valid.peek().litToBoolean, label)
          val nonFinite = !sphere.forall(finite(cfg, _))
          assert(dut.io.out.nonFinite.peek().litToBoolean == nonFinite, s"$label: nonFinite")
          if (!nonFinite) {
            val cells = sphere.take(3).map(model.cell(_, level).get)
            val over = cells.exists(c => math.abs(c) > bp.cellLimit)
            assert(dut.io.out.cellOverflow.peek().litToBoolean == over, s"$label: cellOverflow (model cells $cells)")
            if (over) overflowed += 1
            if (!over) {
              inRange += 1
              cells.zipWithIndex.foreach { case (c, i) => assert(dut.io.out.cell(i).peek().litValue == c, s"$label: cell $i") }
              val (qx, qy, qz, qr) = model.boxKey(sphere, level)
              Seq(qx, qy, qz).zipWithIndex.foreach { case (q, i) => assert(dut.io.out.q(i).peek().litValue == q, s"$label: q $i") }
              assert(dut.io.out.qr.peek().litValue == qr.min(qrMax), s"$label: qr")
            }
            val tops = sphere.take(3).flatMap(model.topExp).filter(_ != Int.MinValue)
            assert(dut.io.out.topNone.peek().litToBoolean == tops.isEmpty, s"$label: topNone")
            if (tops.nonEmpty) assert(dut.io.out.top.peek().litValue == tops.max, s"$label: top")
            val rPositive = SoftFloat.decode(cfg.params, r) match { case Decoded.Finite(false, _, _) => true; case _ => false }
            assert(dut.io.out.needNone.peek().litToBoolean == !rPositive, s"$label: needNone")
            if (rPositive) { needs += 1; assert(dut.io.out.need.peek().litValue == model.need(r), s"$label: need") }
          }
        }
        for (t <- 0 until cases.length + latency) {
          if (t < cases.length) {
            val (sphere, level) = cases(t)
            sphere.zipWithIndex.foreach { case (b, i) => dut.io.in.sphere(i).poke(b.U) }
            dut.io.in.level.poke(level.S); dut.io.in.valid.poke(true.B)
          } else dut.io.in.valid.poke(false.B)
          if (t >= latency) check(t - latency) else assert(!dut.io.out.valid.peek().litToBoolean, s"nothing out at cycle $t")
          dut.clock.step()
        }
      }
      println(s"[SphereKeysSpec ${cfg.name} e$steps latency $latency] ${vs.length} spheres: $inRange cells and box keys compared, $overflowed overflows, $needs needs")
      assert(inRange > vs.length / 3 && overflowed > 0 && needs > vs.length / 6, "the cases should cover all three outcomes")
    }
  }

  it should "hold its outputs a cycle later when built with latency 1 and pass them through with latency 0" in {
    val bp = BroadPhaseParams.default.copy(cellSteps = 2)
    val f = FloatFormat.fp32
    def bits(v: Double) = ScpuModel.fromDouble(f, v)
    test(new SphereKeys(ScpuConfig.fp32.params, bp, latency = 0)) { dut =>
      Seq(-2.5, 0.0, 3.0, 0.5).zipWithIndex.foreach { case (v, i) => dut.io.in.sphere(i).poke(bits(v).U) }
      dut.io.in.level.poke(0.S)
      assert(dut.io.out.cell.map(_.peek().litValue) == Seq(-3, 0, 3)) // floor(-2.5) = -3, same cycle
      assert(dut.io.out.need.peek().litValue == 1)                  // 2 * 0.5 * 9/8 = 1.125 -> 1.5, level 1
      dut.io.in.level.poke(1.S)                                     // edge 1.5
      assert(dut.io.out.cell.map(_.peek().litValue) == Seq(-2, 0, 2)) // floor(-2.5 / 1.5) = -2, floor(3 / 1.5) = 2
    }
  }

  it should "divide every signed 10-bit value by three with floor, as floorDiv3 does in the cells" in {
    class Div3 extends Module {
      val io = IO(new Bundle { val c = Input(SInt(10.W)); val q = Output(SInt(10.W)) })
      io.q := SphereKeys.floorDiv3(io.c)
    }
    test(new Div3) { dut =>
      for (c <- -512 until 512) {
        dut.io.c.poke(c.S)
        assert(dut.io.q.peek().litValue == Math.floorDiv(c, 3), s"floor($c / 3)")
      }
    }
  }
}
