package collide.fp

import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.RootAlgorithm.NewtonRaphson
import collide.fp.model.NewtonRaphsonModel
import collide.testutil.Seeds

/** Measures the Newton-Raphson cores' error against exact arithmetic (through the golden
  * model, which NewtonRaphsonCoreSpec ties to the RTL bit for bit) and holds it to
  * NewtonRaphsonBounds, the numbers docs/fp/newton-raphson.md prints. */
class NewtonRaphsonErrorSpec extends AnyFlatSpec {
  import NewtonRaphsonErrorMeter._
  behavior of "A Newton-Raphson core"

  for ((n, settings) <- NewtonRaphsonBounds.tabulated; nr <- settings; op <- RootOp.all) {
    val bound = NewtonRaphsonBounds.ulpBound(op, nr, n)
    val how = if (exhaustive(n)) "over every significand" else s"on ${Seeds.cases(20000)} sampled significands and every seed-interval edge"
    val claim = if (NewtonRaphsonBounds.faithful(op, nr, n)) f"faithful, $bound%.4g ulp" else f"$bound%.4g ulp"
    it should s"stay within its bound ($claim) after RNE for ${op.name} at sigBits $n with ${nr.name}, $how" in {
      val rng = Seeds.rng(s"NewtonRaphsonErrorSpec-${op.name}-s$n-${nr.name}")
      val st = measure(op, nr, n, cases(op, nr, n, Seeds.cases(20000), rng), bound)
      info(f"${st.count} cases: worst ${st.pre.ulps}%.4f ulp before rounding, ${st.rne.ulps}%.4f after RNE " +
        f"(sig 0x${st.rne.sig.toString(16)} expOdd ${st.rne.expOdd}); bound $bound%.4g")
      assert(st.expDecWrong.isEmpty, s"expDec wrong for ${st.expDecWrong.take(5)}")
      assert(st.outsideBound.isEmpty,
        s"${st.outsideBound.size} results beyond $bound ulp, e.g. ${st.outsideBound.take(5).map { case (s, o) => s"0x${s.toString(16)} odd=$o" }}")
      val apriori = NewtonRaphsonBounds.analyticBound(op, nr, n)
      assert(st.pre.ulps + 0.5 <= apriori, s"measured ${st.pre.ulps} ulp before rounding breaks the a priori bound $apriori")
      if (NewtonRaphsonBounds.faithful(op, nr, n)) assert(st.notFaithful == 0, s"${st.notFaithful} results not faithful")
    }
  }

  it should "document a measured bound for every exhaustively measured setting, none above the a priori bound" in {
    val keys = (for ((n, ss) <- NewtonRaphsonBounds.tabulated if exhaustive(n); nr <- ss; op <- RootOp.all)
      yield (op.name, nr.name, n)).toSet
    for (((op, nr, n), b) <- NewtonRaphsonBounds.documented) {
      assert(keys.contains((op, nr, n)), s"documented bound for untabulated $op $nr sigBits $n")
      val o = RootOp.all.find(_.name == op).get
      val a = NewtonRaphsonBounds.analyticBound(o, RootAlgorithm.parse(nr).toOption.get.asInstanceOf[NewtonRaphson], n)
      assert(b <= a, s"$op $nr sigBits $n: documented $b above a priori $a")
    }
    assert(keys.forall(NewtonRaphsonBounds.documented.contains), s"tabulated but undocumented: ${keys.filterNot(NewtonRaphsonBounds.documented.contains)}")
  }

  it should "offer faithful settings cheapest first, with nr8x2 faithful for fp32 and nr6x1 not faithful for fp24 reciprocals" in {
    for (n <- Seq(8, 11, 16, 24, 53); op <- RootOp.all) {
      val fs = NewtonRaphsonBounds.faithfulSettings(op, n)
      assert(fs.nonEmpty, s"no faithful setting for ${op.name} at $n")
      assert(fs.forall(NewtonRaphsonBounds.faithful(op, _, n)))
      val (small, big) = fs.partition(_.seedBits <= NewtonRaphsonBounds.preferredMaxSeedBits)
      assert(fs == small ++ big, s"big seed tables not last: $fs")
      for (part <- Seq(small, big)) {
        val order = part.map(nr => (nr.iterations, nr.seedBits))
        assert(order == order.sorted, s"not cheapest first: $order")
      }
    }
    assert(RootOp.all.forall(NewtonRaphsonBounds.faithful(_, NewtonRaphson(8, 2), 24)))
    assert(!NewtonRaphsonBounds.faithful(RootOp.Recip, NewtonRaphson(6, 1), 16))
    assert(NewtonRaphsonBounds.cheapestFaithful(24).contains(NewtonRaphson(6, 2)), NewtonRaphsonBounds.cheapestFaithful(24))
    assert(NewtonRaphsonBounds.cheapestFaithful(53).contains(NewtonRaphson(6, 3)), NewtonRaphsonBounds.cheapestFaithful(53))
  }

  it should "hold seeds within the interval error the widths were chosen for" in {
    // Half the interval's relative width plus the seed's rounding (s+3 fraction bits, y0 > 1/2).
    for (op <- RootOp.all; s <- 3 to 12) {
      val plan = NewtonRaphsonCore.Plan(op, 53, NewtonRaphson(s, 1))
      val half = if (op == RootOp.Recip) math.pow(2, -(s + 1)) else math.pow(2, -(s + 2))
      assert(plan.seedRelError <= half + math.pow(2, -(s + 3)), s"${op.name} s=$s: seed error ${plan.seedRelError}")
      assert(plan.seedTable.forall(v => v >= 0 && v < (BigInt(1) << plan.romWidth)))
    }
  }

  it should "measure errors in double arithmetic that agree with exact integer arithmetic" in {
    val rng = Seeds.rng("NewtonRaphsonErrorSpec-meter")
    for (_ <- 0 until Seeds.cases(2000); op <- RootOp.all) {
      val n = Seq(8, 11, 16, 24)(rng.nextInt(4))
      val sig = (BigInt(1) << (n - 1)) + BigInt(n - 1, rng.self)
      val odd = rng.nextBoolean()
      val (raw, _) = NewtonRaphsonModel.rawAndCore(op, NewtonRaphson(6, 1), n, sig, odd)
      val d = ulpsError(op, n, sig, odd, raw.value, raw.fracBits)
      val e = ulpsErrorExact(op, n, sig, odd, raw.value, raw.fracBits)
      assert(math.abs(d - e) < 1e-6, s"${op.name} n=$n sig=0x${sig.toString(16)}: double $d, exact $e")
      assert(within(op, n, sig, odd, raw.value, raw.fracBits, e + 1e-9) && !within(op, n, sig, odd, raw.value, raw.fracBits, e - 1e-9))
    }
  }
}
