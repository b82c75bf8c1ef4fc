package collide.fp

import chiseltest._
import chiseltest.simulator.{VerilatorCFlags, VerilatorFlags}
import org.scalatest.flatspec.AnyFlatSpec
import collide.fp.model.{FpResult, RootModel}
import collide.testutil.{Seeds, Slow}
import RootTestKit._

/** The checks every root-type operator spec runs (FpSqrtSpec, FpRecipSpec, FpRsqrtSpec):
  * golden model vs independent oracles (JVM where one exists, exact integer arithmetic in
  * every mode), exhaustive 16-bit formats, and RTL vs golden for every preset format.
  */
abstract class RootSpecBase(op: RootOp) extends AnyFlatSpec with ChiselScalatestTester {
  val opName = s"Fp${op.name.capitalize}"
  val dr: RootAlgorithm = RootAlgorithm.DigitRecurrence
  def golden(p: FpParams, a: BigInt, rm: RoundingMode): FpResult = RootModel(op, p, dr, a, rm)
  val jvmName: String = op match { case RootOp.Sqrt => "Math.sqrt"; case _ => "1/x" }

  def checkSame(what: String, f: FloatFormat, a: BigInt, rm: RoundingMode, got: FpResult, want: FpResult): Unit =
    assert(got == want, s"$opName $what ${f.name} a=${showBits(f, a)} $rm: golden ${got.show(f)}, oracle ${want.show(f)}")

  def jvmCheck(p: FpParams, ops: Iterator[BigInt]): Int = {
    var n = 0
    for (a <- ops) {
      val want = jvmRne(op, p.format, a).get
      val got  = golden(p, a, RoundingMode.RNE).bits
      assert(got == want, s"$opName ${p.name} a=${showBits(p.format, a)} RNE: golden ${showBits(p.format, got)}, JVM ${showBits(p.format, want)}")
      n += 1
    }
    n
  }

  def exactCheck(p: FpParams, ops: Iterator[BigInt], modes: Seq[RoundingMode]): Int = {
    var n = 0
    for (a <- ops; rm <- modes) {
      checkSame("vs exact", p.format, a, rm, golden(p, a, rm), ExactOracle(op, p, a, rm)); n += 1
    }
    n
  }

  // ---- golden model vs JVM (only sqrt and recip have one)
  if (op != RootOp.Rsqrt) {
    for (p <- Seq(FpParams.fp32, FpParams.fp64)) {
      val n = Seeds.cases(100000)
      it should s"match the JVM's $jvmName in RNE on corner operands and $n random ${p.name} operands (golden, digit recurrence)" in {
        val rng = Seeds.rng(s"$opName-jvm-${p.name}")
        val c = jvmCheck(p, corners(p.format).iterator ++ Iterator.fill(n)(randomOperand(p.format, rng)))
        info(s"$c operands")
      }
    }
  }

  // ---- the exact oracle itself (the only one rsqrt has) against the JVM
  if (op != RootOp.Rsqrt) {
    val n = Seeds.cases(20000)
    it should s"have an exact oracle that agrees with the JVM's $jvmName in RNE ($n random fp32 and fp64 operands)" in {
      for (p <- Seq(FpParams.fp32, FpParams.fp64)) {
        val rng = Seeds.rng(s"$opName-oracle-${p.name}")
        for (a <- corners(p.format).iterator ++ Iterator.fill(n)(randomOperand(p.format, rng))) {
          val want = jvmRne(op, p.format, a).get
          val got  = ExactOracle(op, p, a, RoundingMode.RNE).bits
          assert(got == want, s"$opName ${p.name} a=${showBits(p.format, a)}: oracle ${showBits(p.format, got)}, JVM ${showBits(p.format, want)}")
        }
      }
    }
  }

  // ---- golden model vs exact integer oracle, every mode
  for (p <- Seq(FpParams.fp32, FpParams.fp64, FpParams(FloatFormat.fp24), FpParams(FloatFormat.fp32, subnormals = false))) {
    val n = Seeds.cases(if (op == RootOp.Rsqrt && p == FpParams.fp32) 100000 else if (p.format == FloatFormat.fp64) 10000 else 20000)
    it should s"round exactly in every mode on corner operands and $n random ${p.name} operands (golden vs exact oracle)" in {
      val rng = Seeds.rng(s"$opName-exact-${p.name}")
      val cornersN = exactCheck(p, corners(p.format).iterator, RoundingMode.all)
      // random operands each in one random mode, plus RNE for all (RNE is the default mode)
      var c = cornersN
      for (_ <- 0 until n) {
        val a = randomOperand(p.format, rng)
        c += exactCheck(p, Iterator(a), Seq(RoundingMode.RNE, RoundingMode.all(1 + rng.nextInt(4))))
      }
      info(s"$c (operand, mode) pairs")
    }
  }

  // ---- exhaustive 16-bit formats
  for (f <- Seq(FloatFormat.fp16, FloatFormat.bf16)) {
    if (op != RootOp.Rsqrt)
      it should s"match the JVM's $jvmName through float on every one of the 65536 ${f.name} inputs (RNE)" in {
        jvmCheck(FpParams(f), Iterator.range(0, 1 << 16).map(BigInt(_)))
      }
    it should s"round exactly on every one of the 65536 ${f.name} inputs in every mode, subnormals kept and flushed" in {
      for (p <- Seq(FpParams(f), FpParams(f, subnormals = false)))
        exactCheck(p, Iterator.range(0, 1 << 16).map(BigInt(_)), RoundingMode.all)
    }
  }

  // ---- RTL vs golden
  def rtlCheck(p: FpParams, alg: RootAlgorithm, latency: Int, n: Int): Unit = {
    val rng = Seeds.rng(s"$opName-rtl-${p.name}-${alg.name}-L$latency")
    val f = p.format
    // fp64 simulates slowly in treadle (about 10k nodes): fewer powers of two among its corners
    val ops = corners(f, if (f == FloatFormat.fp64) 8 else 40) ++ Seq.fill(n)(randomOperand(f, rng))
    val vectors = ops.flatMap(a => Seq((a, RoundingMode.all(rng.nextInt(5))))) ++
      corners(f).take(12).flatMap(a => RoundingMode.all.map(rm => (a, rm)))
    val t0 = System.nanoTime(); var t1 = t0
    val annos = if (sys.props.get("rootsVerilator").isDefined && f == FloatFormat.fp64)
      Seq(VerilatorBackendAnnotation, VerilatorCFlags(Seq("-O1")), VerilatorFlags(Seq("-O0"))) else Seq()
    test(build(op, p, alg, latency)).withAnnotations(annos) { c =>
      assert(c.latency == latency)
      t1 = System.nanoTime()
      stream(c, vectors, rng, (a, rm) => RootModel(op, p, alg, a, rm))
    }
    val t2 = System.nanoTime()
    println(f"[$opName ${p.name} ${alg.name} L$latency] build ${(t1 - t0) / 1e9}%.1f s, ${vectors.size} vectors ${(t2 - t1) / 1e9}%.1f s")
  }

  /** Pipelined latency under test: core registers every other iteration (plus the operator's two). */
  def pipelined(f: FloatFormat): Int = 2 + f.sigBits / 2

  for ((name, f) <- FloatFormat.presets) {
    val n = Seeds.cases(if (f == FloatFormat.fp64) 40 else 250)
    // flushed: every stage registered, one a core iteration and the unpack's and the rounder's
    // seven (RootLatency; fp64: the pipelined latency, to keep treadle quick)
    val ftzLatency = if (f == FloatFormat.fp64) pipelined(f) + 1 else RootCoreSelect.cuts(op, f.sigBits, dr) + 7
    it should s"match its golden model in RTL for $name, latency 0 and ${pipelined(f)}, and flushed at latency $ftzLatency, every mode ($n random operands each)" in {
      rtlCheck(FpParams(f), dr, 0, n)
      rtlCheck(FpParams(f), dr, pipelined(f), n)
      rtlCheck(FpParams(f, subnormals = false), dr, ftzLatency, n)
    }
  }

  // Newton-Raphson (core and its model from branch fp-nr): the operator around it must stay
  // bit-exact with RootModel, whatever the core's accuracy.
  for ((p, nr, l) <- Seq((FpParams(FloatFormat.fp16), RootAlgorithm.NewtonRaphson(6, 1), 0),
                         (FpParams(FloatFormat.fp32, subnormals = false), RootAlgorithm.NewtonRaphson(8, 2), 5),
                         (FpParams(FloatFormat.fp16), RootAlgorithm.NewtonRaphson(6, 1),
                           NewtonRaphsonCore.naturalLatency(op, RootAlgorithm.NewtonRaphson(6, 1)) + 7))) {
    val n = Seeds.cases(150)
    it should s"match its golden model in RTL with Newton-Raphson ${nr.name} for ${p.name} at latency $l ($n random operands)" in {
      rtlCheck(p, nr, l, n)
    }
  }

  // Deeper, tagged Slow (excluded from the default run): every fp16 input through the RTL.
  it should "match its golden model in RTL on every one of the 65536 fp16 inputs, pipelined, random modes" taggedAs Slow in {
    val p = FpParams(FloatFormat.fp16)
    val rng = Seeds.rng(s"$opName-rtl-exhaustive-fp16")
    val vectors = (0 until (1 << 16)).map(a => (BigInt(a), RoundingMode.all(rng.nextInt(5))))
    test(build(op, p, dr, pipelined(p.format))) { c => stream(c, vectors, rng, (a, rm) => RootModel(op, p, dr, a, rm)) }
  }

  it should "carry every parameter in its Verilog module name" in {
    val ftz16 = FpParams(FloatFormat.fp16, subnormals = false)
    for ((p, alg, l, want) <- Seq((FpParams.fp32, dr, 0, s"${opName}_fp32_dr_L0"), (ftz16, dr, 5, s"${opName}_fp16_ftz_dr_L5"),
                                  (FpParams(FloatFormat.fp16), RootAlgorithm.NewtonRaphson(8, 2), 4, s"${opName}_fp16_nr8x2_L4"))) {
      val chirrtl = circt.stage.ChiselStage.emitCHIRRTL(build(op, p, alg, l))
      assert(chirrtl.contains(s"module $want :"), s"no module $want")
    }
  }
}
