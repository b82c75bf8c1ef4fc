package collide.fp

import chisel3._
import chiseltest._
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.RootAlgorithm.NewtonRaphson
import collide.fp.model.NewtonRaphsonModel
import collide.testutil.{Seeds, Slow}

class NewtonRaphsonCoreSpec extends AnyFlatSpec with ChiselScalatestTester {
  behavior of "NewtonRaphsonCore"

  /** Significands that stress the datapath: m = 1, 1 + ulp, just below 2, both sides of
    * seed-interval boundaries; the rest random. */
  def edgeSigs(n: Int, nr: NewtonRaphson, rng: scala.util.Random): Seq[BigInt] = {
    val one = BigInt(1)
    val s = math.min(nr.seedBits, n - 1)
    val step = one << (n - 1 - s)
    val fixed = Seq(one << (n - 1), (one << (n - 1)) + 1, (one << n) - 1, (one << n) - 2)
    val bounds = Seq.fill(24) {
      val j = 1 + rng.nextInt((1 << s) - 1)
      (one << (n - 1)) + j * step + (if (rng.nextBoolean()) 0 else -1)
    }
    fixed ++ bounds
  }

  /** Streams one input per enabled cycle (en randomly low, input changing while stalled) and
    * checks every output against the golden model `latency` enabled cycles later. */
  def stream(op: RootOp, n: Int, nr: NewtonRaphson, latency: Int, count: Int): Unit = {
    val rng = Seeds.rng(s"NewtonRaphsonCoreSpec-${op.name}-s$n-${nr.name}-L$latency")
    val edges = edgeSigs(n, nr, rng)
    test(new NewtonRaphsonCore(op, n, nr, latency)) { c =>
      // Expected outputs of the inputs taken on enabled cycles, oldest first; None: invalid.
      val inFlight = scala.collection.mutable.Queue.fill[Option[(BigInt, Boolean)]](latency)(None)
      var checked = 0
      var i = 0
      var cycle = 0
      while (checked < count) {
        val sig = if (i < edges.size) edges(i) else (BigInt(1) << (n - 1)) + BigInt(n - 1, rng.self)
        val odd = rng.nextBoolean()
        val valid = rng.nextInt(8) != 0
        val en = latency == 0 || rng.nextInt(5) != 0
        c.io.en.poke(en.B)
        c.io.in.valid.poke(valid.B)
        c.io.in.bits.sig.poke(sig.U)
        c.io.in.bits.expOdd.poke(odd.B)
        val want = if (valid) Some(NewtonRaphsonModel.core(op, nr, n, sig, odd)) else None
        val expect = if (latency == 0) want else inFlight.head
        val gotValid = c.io.out.valid.peek().litToBoolean
        assert(gotValid == expect.isDefined, s"cycle $cycle: out.valid $gotValid, want ${expect.isDefined}")
        for ((wSig, wDec) <- expect) {
          val gSig = c.io.out.bits.sig.peek().litValue
          val gDec = c.io.out.bits.expDec.peek().litToBoolean
          assert(gSig == wSig && gDec == wDec,
            s"cycle $cycle: got sig 0x${gSig.toString(16)} expDec $gDec, want 0x${wSig.toString(16)} expDec $wDec")
          checked += 1
        }
        if (en) {
          if (latency > 0) { inFlight.dequeue(); inFlight.enqueue(want) }
          i += 1
        }
        c.clock.step()
        cycle += 1
      }
    }
  }

  // (sigBits, setting, latency; None = one register per cut) per op: every width, a
  // combinational and a pipelined core. Treadle evaluates a big seed ROM slowly (a 2^11-entry
  // ROM takes tens of seconds), so the default run keeps seeds at 8 bits or fewer; the
  // bigger ROMs run with the Slow tag.
  val configs: Seq[(Int, NewtonRaphson, Option[Int])] = Seq(
    (8, NewtonRaphson(6, 0), Some(1)), (8, NewtonRaphson(6, 1), Some(0)), (8, NewtonRaphson(8, 1), None),
    (11, NewtonRaphson(6, 1), None), (11, NewtonRaphson(8, 2), Some(0)),
    (16, NewtonRaphson(8, 1), Some(0)), (16, NewtonRaphson(6, 2), None),
    (24, NewtonRaphson(8, 2), None), (24, NewtonRaphson(6, 3), Some(0)),
    (53, NewtonRaphson(8, 3), Some(3)), (53, NewtonRaphson(6, 4), Some(0))
  )
  val slowConfigs: Seq[(Int, NewtonRaphson, Option[Int])] = Seq(
    (24, NewtonRaphson(10, 2), Some(0)), (53, NewtonRaphson(12, 3), None)
  )

  for (op <- RootOp.all; (n, nr, lat) <- configs) {
    val latency = lat.getOrElse(NewtonRaphsonCore.naturalLatency(op, nr))
    it should s"match the golden model bit for bit for ${op.name}, sigBits $n, ${nr.name}, latency $latency" in {
      stream(op, n, nr, latency, Seeds.cases(300))
    }
  }
  for (op <- RootOp.all; (n, nr, lat) <- slowConfigs) {
    val latency = lat.getOrElse(NewtonRaphsonCore.naturalLatency(op, nr))
    it should s"match the golden model bit for bit for ${op.name}, sigBits $n, ${nr.name}, latency $latency (big seed ROM)" taggedAs Slow in {
      stream(op, n, nr, latency, Seeds.cases(300))
    }
  }

  it should "name every parameter in its module name" in {
    val nr = NewtonRaphson(8, 2)
    val name = circt.stage.ChiselStage.emitSystemVerilog(new NewtonRaphsonCore(RootOp.Rsqrt, 24, nr, 6)).linesIterator
      .collectFirst { case l if l.startsWith("module ") => l }.getOrElse("")
    assert(name.contains("NewtonRaphsonCore_rsqrt_s24_nr8x2_L6"), name)
  }

  it should "reject a negative or excessive latency with a message naming it" in {
    val nr = NewtonRaphson(8, 1)
    val e = intercept[IllegalArgumentException](NewtonRaphsonCore.check(RootOp.Recip, 24, nr, -1))
    assert(e.getMessage.contains("latency"), e.getMessage)
    intercept[IllegalArgumentException](NewtonRaphsonCore.check(RootOp.Recip, 24, nr, NewtonRaphsonCore.maxLatency(RootOp.Recip, nr) + 1))
  }
}
