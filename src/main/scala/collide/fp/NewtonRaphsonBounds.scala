package collide.fp

/** Error bounds of the Newton-Raphson cores, in ulps of the returned w in [1,2) (units of
  * 2^-(sigBits-1)), after round-to-nearest-even. One source for the tests
  * (NewtonRaphsonErrorSpec asserts the measured worst case stays within [[ulpBound]]), the
  * documentation (docs/fp/newton-raphson.md) and the presets ([[faithful]]).
  */
object NewtonRaphsonBounds {
  import RootAlgorithm.NewtonRaphson

  /** Settings measured and documented per sigBits (exhaustively for sigBits <= 16, sampled
    * for wider formats); the error table in docs/fp/newton-raphson.md lists exactly these. */
  val tabulated: Seq[(Int, Seq[NewtonRaphson])] = Seq(
    8  -> Seq(NewtonRaphson(6, 0), NewtonRaphson(8, 0), NewtonRaphson(4, 1), NewtonRaphson(6, 1), NewtonRaphson(8, 1)),
    11 -> Seq(NewtonRaphson(8, 0), NewtonRaphson(4, 1), NewtonRaphson(6, 1), NewtonRaphson(8, 1), NewtonRaphson(6, 2)),
    16 -> Seq(NewtonRaphson(6, 1), NewtonRaphson(8, 1), NewtonRaphson(10, 1), NewtonRaphson(4, 2), NewtonRaphson(6, 2), NewtonRaphson(8, 2)),
    24 -> Seq(NewtonRaphson(12, 1), NewtonRaphson(6, 2), NewtonRaphson(8, 2), NewtonRaphson(10, 2), NewtonRaphson(6, 3)),
    53 -> Seq(NewtonRaphson(8, 2), NewtonRaphson(6, 3), NewtonRaphson(8, 3), NewtonRaphson(10, 3), NewtonRaphson(12, 3), NewtonRaphson(6, 4))
  )

  /** Documented bounds where the measurement is exhaustive (sigBits <= 16: every
    * significand, both exponent parities): the measured worst case after RNE
    * (`Test/runMain collide.fp.NewtonRaphsonErrorTable`), rounded up to two significant
    * digits. Keyed by (op name, setting name, sigBits). Sampled widths (24, 53) document the
    * a priori bound instead: a sample cannot prove a worst case. */
  val documented: Map[(String, String, Int), Double] = Map(
    ("sqrt", "nr6x0", 8) -> 1.5,
    ("recip", "nr6x0", 8) -> 2.6,
    ("rsqrt", "nr6x0", 8) -> 1.5,
    ("sqrt", "nr8x0", 8) -> 0.86,
    ("recip", "nr8x0", 8) -> 1.5,
    ("rsqrt", "nr8x0", 8) -> 1.1,
    ("sqrt", "nr4x1", 8) -> 0.54,
    ("recip", "nr4x1", 8) -> 0.58,
    ("rsqrt", "nr4x1", 8) -> 0.56,
    ("sqrt", "nr6x1", 8) -> 0.54,
    ("recip", "nr6x1", 8) -> 0.54,
    ("rsqrt", "nr6x1", 8) -> 0.53,
    ("sqrt", "nr8x1", 8) -> 0.54,
    ("recip", "nr8x1", 8) -> 0.54,
    ("rsqrt", "nr8x1", 8) -> 0.53,
    ("sqrt", "nr8x0", 11) -> 2.5,
    ("recip", "nr8x0", 11) -> 4.3,
    ("rsqrt", "nr8x0", 11) -> 2.5,
    ("sqrt", "nr4x1", 11) -> 1.5,
    ("recip", "nr4x1", 11) -> 2.1,
    ("rsqrt", "nr4x1", 11) -> 1.3,
    ("sqrt", "nr6x1", 11) -> 0.56,
    ("recip", "nr6x1", 11) -> 0.64,
    ("rsqrt", "nr6x1", 11) -> 0.55,
    ("sqrt", "nr8x1", 11) -> 0.55,
    ("recip", "nr8x1", 11) -> 0.56,
    ("rsqrt", "nr8x1", 11) -> 0.53,
    ("sqrt", "nr6x2", 11) -> 0.55,
    ("recip", "nr6x2", 11) -> 0.56,
    ("rsqrt", "nr6x2", 11) -> 0.53,
    ("sqrt", "nr6x1", 16) -> 2.2,
    ("recip", "nr6x1", 16) -> 4.9,
    ("rsqrt", "nr6x1", 16) -> 2.5,
    ("sqrt", "nr8x1", 16) -> 0.62,
    ("recip", "nr8x1", 16) -> 0.77,
    ("rsqrt", "nr8x1", 16) -> 0.62,
    ("sqrt", "nr10x1", 16) -> 0.58,
    ("recip", "nr10x1", 16) -> 0.58,
    ("rsqrt", "nr10x1", 16) -> 0.53,
    ("sqrt", "nr4x2", 16) -> 0.58,
    ("recip", "nr4x2", 16) -> 0.6,
    ("rsqrt", "nr4x2", 16) -> 0.54,
    ("sqrt", "nr6x2", 16) -> 0.56,
    ("recip", "nr6x2", 16) -> 0.56,
    ("rsqrt", "nr6x2", 16) -> 0.54,
    ("sqrt", "nr8x2", 16) -> 0.56,
    ("recip", "nr8x2", 16) -> 0.58,
    ("rsqrt", "nr8x2", 16) -> 0.54
  )

  /** A priori bound after RNE, valid for every setting: the seed ROM's exact worst relative
    * error e0 (NewtonRaphsonCore.Plan.seedRelError) carried through the iterations with the
    * truncation of every product (u = 2^-F):
    *   Recip: |e'| <= e^2 + (3 + |e|) u
    *   Rsqrt: |e'| <= 3/2 e^2 + 1/2 |e|^3 + 5/2 (1 + |e|) u
    *   Sqrt:  Rsqrt's bound, then the final product: |e| + 2u;
    * then |w' - w| <= |e| w < |e| 2 ulps 2^(sigBits-1), plus half an ulp for rounding.
    * Clamps and saturation only move the value toward the exact one. */
  def analyticBound(op: RootOp, nr: NewtonRaphson, sigBits: Int): Double = {
    val plan = NewtonRaphsonCore.Plan.cached(op, sigBits, nr)
    val u = math.pow(2, -plan.F)
    var e = plan.seedRelError * (1 + 1e-9) + 1e-18 // margin for the double evaluation
    for (_ <- 0 until nr.iterations) e = op match {
      case RootOp.Recip => e * e + (3 + e) * u
      case _            => 1.5 * e * e + 0.5 * e * e * e + 2.5 * (1 + e) * u
    }
    if (op == RootOp.Sqrt) e += 2 * u
    e * math.pow(2, sigBits) + 0.5
  }

  /** The bound the tests hold the core to and the docs print: the documented measurement
    * where there is one (never above the a priori bound), else the a priori bound. */
  def ulpBound(op: RootOp, nr: NewtonRaphson, sigBits: Int): Double = {
    val a = analyticBound(op, nr, sigBits)
    documented.get((op.name, nr.name, sigBits)).fold(a)(math.min(_, a))
  }

  /** Faithful: every result is one of the two representable neighbours of the exact value
    * (error < 1 ulp after RNE). */
  def faithful(op: RootOp, nr: NewtonRaphson, sigBits: Int): Boolean = ulpBound(op, nr, sigBits) < 1.0

  /** Seed ROMs above this many index bits (2^11 x 12 bits for the roots) are offered only
    * after every smaller one: a 12-bit table is 8192 x 14 bits, several block RAMs. */
  val preferredMaxSeedBits: Int = 10

  /** Settings the presets choose from, cheapest first: seed tables of at most
    * [[preferredMaxSeedBits]] by (iterations, seedBits) (iterations cost wide multipliers and
    * latency), then the bigger tables in the same order. */
  val candidates: Seq[NewtonRaphson] = {
    val all = for (it <- 0 to 4; sb <- 4 to 12) yield NewtonRaphson(sb, it)
    val (small, big) = all.partition(_.seedBits <= preferredMaxSeedBits)
    small ++ big
  }

  /** The candidate settings that are faithful for `op` at `sigBits`, cheapest first. */
  def faithfulSettings(op: RootOp, sigBits: Int): Seq[NewtonRaphson] =
    candidates.filter(faithful(op, _, sigBits))

  /** The cheapest faithful setting for every op at once (what a unit sharing one setting
    * for sqrt, recip and rsqrt needs). */
  def cheapestFaithful(sigBits: Int, ops: Seq[RootOp] = RootOp.all): Option[NewtonRaphson] =
    candidates.find(nr => ops.forall(faithful(_, nr, sigBits)))
}
