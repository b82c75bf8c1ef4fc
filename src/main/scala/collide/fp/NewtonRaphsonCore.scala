package collide.fp

import chisel3._
import chisel3.util._

/** Table-seeded Newton-Raphson significand core for reciprocal, reciprocal square root and
  * square root, in fixed-point integer arithmetic (docs/fp/newton-raphson.md).
  *
  * Implements [[RootCoreIO]]: x = m in [1,2) (Recip) or x = m or 2m in [1,4) (Sqrt, Rsqrt);
  * returns an approximation of w = v or 2v in [1,2) in RoundIn layout, expDec exact.
  *
  * Datapath (widths in [[NewtonRaphsonCore.Plan]]; n = sigBits, F = n + guard bits):
  *  - seed: a ROM indexed by the leading fraction bits of m (and the exponent parity for
  *    the roots) gives y0 ~ 1/x or 1/sqrt(x) in (1/2,1) with s+3 fraction bits;
  *  - Recip:  P = xy (truncated to F fraction bits), E = ~P = 2 - xy - 2^-F, y' = yE;
  *  - Rsqrt:  Y2 = y^2, T = x*Y2, E = 3 - T, y' = yE/2;
  *  - Sqrt:   rsqrt iterations, then s = x*y;
  *  every product truncated to F fraction bits, y saturated below 1 after each step.
  *  The result is clamped into [1, 2) (only ever moving it toward the exact value), and
  *  x = 1 gives an exact 1 for Recip and Rsqrt.
  *
  * Pipeline: register cuts after the seed lookup, after every multiply but the last, and at
  * the output (after formatting); `latency` registers are spread over them with
  * [[Pipeline.placement]] (output first). Fully pipelined; `io.en` low holds everything.
  */
class NewtonRaphsonCore(op: RootOp, sigBits: Int, nr: RootAlgorithm.NewtonRaphson, latency: Int) extends Module {
  NewtonRaphsonCore.check(op, sigBits, nr, latency)
  val io = IO(new RootCoreIO(sigBits))

  val plan: NewtonRaphsonCore.Plan = NewtonRaphsonCore.Plan(op, sigBits, nr)
  import plan.{n, F, s}

  override def desiredName = s"NewtonRaphsonCore_${op.name}_s${sigBits}_${nr.name}_L$latency"

  private val regs = Pipeline.placement(latency, plan.stages)
  private var nextCut = 0
  /** Places the registers of the next cut on every signal given (they travel together). */
  private def cut[T <: Data](xs: T*): Seq[T] = {
    val k = regs(nextCut)
    xs.map(x => Pipeline(x, k, io.en))
  }
  private def cutValid(v: Bool): Bool = {
    val k = regs(nextCut); nextCut += 1
    Pipeline.valid(v, k, io.en)
  }

  // ---- Input decode and seed lookup ----
  private val sig    = io.in.bits.sig
  private val isRoot = op != RootOp.Recip
  private val odd    = if (isRoot) io.in.bits.expOdd else false.B
  // x with n-1 fraction bits; n+1 bits for the roots (x < 4), n for Recip (x < 2).
  private val x0: UInt = if (isRoot) Mux(odd, Cat(sig, 0.U(1.W)), Cat(0.U(1.W), sig)) else sig
  private val isOne0 = !odd && sig === (BigInt(1) << (n - 1)).U
  private val frac   = sig(n - 2, n - 1 - s)
  private val index  = if (isRoot) Cat(odd, frac) else frac
  private val rom    = VecInit(plan.seedTable.map(_.U((s + 2).W)))
  private val y0     = Cat(1.U(1.W), rom(index)) << (F - s - 3) // F fraction bits, y0 in (1/2,1)

  private var valid = io.in.valid
  private var x     = x0
  private var isOne = isOne0
  private var y: UInt = y0(F - 1, 0)

  /** Registers the live signals at the next cut (not used for the output cut). */
  private def cutAll(extra: UInt): UInt = {
    val Seq(xx, yy, ee) = cut(x, y, extra)
    isOne = cut(isOne).head
    x = xx; y = yy
    valid = cutValid(valid)
    ee
  }
  if (plan.multiplies > 0) cutAll(0.U(1.W)) // after the seed lookup

  private var mulsDone = 0
  /** After a multiply: a cut unless it was the last one (whose cut is the output's). */
  private def afterMul(v: UInt): UInt = {
    mulsDone += 1
    if (mulsDone < plan.multiplies) cutAll(v) else v
  }

  private val satMax = ((BigInt(1) << F) - 1).U(F.W)
  private def saturate(v: UInt): UInt = Mux(v > satMax, satMax, v(F - 1, 0))

  for (_ <- 0 until nr.iterations) {
    op match {
      case RootOp.Recip =>
        val p  = afterMul(((x * y) >> (n - 1))(F, 0))     // xy, F fraction bits, < 2
        val e  = ~p                                       // 2 - xy - 2^-F, F+1 bits
        y = saturate(afterMul((y * e) >> F))
      case RootOp.Rsqrt | RootOp.Sqrt =>
        val y2 = afterMul(((y * y) >> F)(F - 1, 0))       // y^2 < 1
        val t  = afterMul(((x * y2) >> (n - 1))(F + 1, 0)) // x y^2, < 4
        val e  = ((BigInt(3) << F).U((F + 2).W) - t)(F + 1, 0) // 3 - x y^2
        y = saturate(afterMul((y * e) >> (F + 1)))
    }
  }

  // ---- Output formatting (RoundIn layout: n result bits, round, sticky) ----
  private val outSig = Wire(UInt((n + 2).W))
  private val outDec = Wire(Bool())
  op match {
    case RootOp.Sqrt =>
      val sq  = afterMul(((x * y) >> (n - 1))(F + 1, 0)) // sqrt(x) with F fraction bits
      val lo  = (BigInt(1) << F).U
      val hi  = ((BigInt(1) << (F + 1)) - 1).U
      val sc  = Mux(sq < lo, lo, Mux(sq > hi, hi, sq))
      outSig := Cat(sc(F, F - n), sc(F - n - 1, 0).orR)
      outDec := false.B
    case _ =>
      // w = 2y: y's F fraction bits read as w with F-1 fraction bits.
      val half = (BigInt(1) << (F - 1)).U(F.W)
      val w    = Mux(y < half, half, y)
      outSig := Mux(isOne, (BigInt(1) << (n + 1)).U, Cat(w(F - 1, F - n - 1), w(F - n - 2, 0).orR))
      outDec := !isOne
  }
  private val oSig = cut(outSig).head
  private val oDec = cut(outDec).head
  io.out.valid       := cutValid(valid)
  io.out.bits.sig    := oSig
  io.out.bits.expDec := oDec
  require(nextCut == plan.stages, s"internal: placed $nextCut cuts, planned ${plan.stages}")
}

object NewtonRaphsonCore {
  /** Latency bounds: any number of registers from 0 up; [[naturalLatency]] puts one at every cut. */
  val minLatency: Int = 0
  def maxLatency(op: RootOp, nr: RootAlgorithm.NewtonRaphson): Int = 4 * naturalLatency(op, nr)
  /** One register per cut: after the seed ROM, after each multiply, at the output. */
  def naturalLatency(op: RootOp, nr: RootAlgorithm.NewtonRaphson): Int = stages(op, nr)

  def multipliesPerIteration(op: RootOp): Int = op match {
    case RootOp.Recip => 2
    case _            => 3
  }
  def multiplies(op: RootOp, nr: RootAlgorithm.NewtonRaphson): Int =
    nr.iterations * multipliesPerIteration(op) + (if (op == RootOp.Sqrt) 1 else 0)
  /** Register cuts: after the seed (when any multiply follows), between multiplies, output. */
  def stages(op: RootOp, nr: RootAlgorithm.NewtonRaphson): Int = multiplies(op, nr) + 1

  /** Guard bits below the result's n bits in the working precision F = n + guardBits. Chosen
    * so that, once the iteration has converged, truncation stays well below half an ulp
    * (docs/fp/newton-raphson.md, "Widths"). */
  def guardBits(op: RootOp): Int = 5

  def check(op: RootOp, sigBits: Int, nr: RootAlgorithm.NewtonRaphson, latency: Int): Unit = {
    require(sigBits >= 3 && sigBits <= 64, s"NewtonRaphsonCore: sigBits must be 3..64, got $sigBits")
    require(latency >= minLatency && latency <= maxLatency(op, nr),
      s"NewtonRaphsonCore ${op.name} ${nr.name}: latency must be $minLatency..${maxLatency(op, nr)}, got $latency")
  }

  object Plan {
    private val cache = new java.util.concurrent.ConcurrentHashMap[(RootOp, Int, RootAlgorithm.NewtonRaphson), Plan]()
    /** One Plan per configuration, so the seed table is computed once (models call this per case). */
    def cached(op: RootOp, sigBits: Int, nr: RootAlgorithm.NewtonRaphson): Plan =
      cache.computeIfAbsent((op, sigBits, nr), _ => { val p = Plan(op, sigBits, nr); p.seedTable; p })
  }

  /** Every width and the seed ROM of one configuration; shared by the RTL and the golden
    * model (NewtonRaphsonModel), which must agree bit for bit. */
  final case class Plan(op: RootOp, sigBits: Int, nr: RootAlgorithm.NewtonRaphson) {
    require(sigBits >= 3 && sigBits <= 64, s"NewtonRaphsonCore: sigBits must be 3..64, got $sigBits")
    val n: Int = sigBits
    /** Working fraction bits of y (y < 1) and of every truncated product. */
    val F: Int = n + guardBits(op)
    /** Index bits taken from the fraction of m (a significand has only n-1 of them). */
    val s: Int = math.min(nr.seedBits, n - 1)
    /** Seed fraction bits: y0 in (1/2,1) is 2^-1 + rom * 2^-(s+3), rom of s+2 bits. */
    val seedFracBits: Int = s + 3
    val romWidth: Int = s + 2
    val isRoot: Boolean = op != RootOp.Recip
    val romEntries: Int = (if (isRoot) 2 else 1) << s
    val multiplies: Int = NewtonRaphsonCore.multiplies(op, nr)
    val stages: Int = NewtonRaphsonCore.stages(op, nr)
    require(F >= seedFracBits, s"internal: working precision $F below seed precision $seedFracBits")

    /** ROM index for significand `sig` (top bit set) and exponent parity. */
    def index(sig: BigInt, expOdd: Boolean): Int = {
      val fr = ((sig >> (n - 1 - s)) & ((BigInt(1) << s) - 1)).toInt
      if (isRoot && expOdd) fr | (1 << s) else fr
    }

    /** The interval [a, b) of x that ROM entry i covers. */
    def interval(i: Int): (Double, Double) = {
      val scale = if (isRoot && (i >> s) == 1) 2.0 else 1.0
      val j = i & ((1 << s) - 1)
      val a = (1.0 + j.toDouble / (1 << s)) * scale
      (a, a + scale / (1 << s))
    }

    /** The exact function whose seed the table holds: 1/x or 1/sqrt(x). */
    def f(x: Double): Double = if (isRoot) 1.0 / math.sqrt(x) else 1.0 / x

    /** Seed of entry i as an integer with seedFracBits fraction bits: the value that makes the
      * relative error equal and opposite at both ends of the interval (for Recip, 1 / the
      * interval's midpoint; for the roots, 2 / (sqrt a + sqrt b)), rounded to nearest. The
      * Newton error depends only on |relative error|, so this minimizes it. */
    def seedValue(i: Int): BigInt = {
      val (a, b) = interval(i)
      val mid = if (isRoot) 2.0 / (math.sqrt(a) + math.sqrt(b)) else 2.0 / (a + b)
      val q = BigInt(math.round(mid * math.pow(2, seedFracBits)))
      val lo = BigInt(1) << (seedFracBits - 1)
      // Clamp into (1/2, 1): f > 1/2 on every interval, so this only ever helps.
      q.max(lo).min((BigInt(1) << seedFracBits) - 1)
    }

    /** The ROM's contents: seedValue without its always-set leading bit (2^-1). */
    lazy val seedTable: IndexedSeq[BigInt] =
      (0 until romEntries).map(i => seedValue(i) - (BigInt(1) << (seedFracBits - 1)))

    /** Largest |relative error| of the seed over its interval (at an end: f is monotone). */
    lazy val seedRelError: Double = (0 until romEntries).map { i =>
      val (a, b) = interval(i)
      val y = seedValue(i).toDouble / math.pow(2, seedFracBits)
      math.max(math.abs(y / f(a) - 1), math.abs(y / f(b) - 1))
    }.max
  }
}
