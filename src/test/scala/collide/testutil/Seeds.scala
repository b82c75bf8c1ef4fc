package collide.testutil

/** Seeds for randomized specs: printed, and settable with -Dseed=N (or env SEED) so any
  * failure can be replayed: `SEED=1234 tools/sbt "testOnly collide.fp.FpAddSpec"` (or -Dseed, which build.sbt forwards
  * to the forked test JVM). Without one, each spec's seed is a hash of its name, mixed with
  * env COLLIDE_RUN_SEED when set: CI draws a new run seed every time (tools/test prints it),
  * so every run tries new cases and a failure still names the seed that replays it.
  */
object Seeds {
  def seed(specName: String): Long = {
    val run = sys.env.get("COLLIDE_RUN_SEED").filter(_.nonEmpty).map(_.trim.toLong).getOrElse(0L)
    val s = sys.props.get("seed").orElse(sys.env.get("SEED")).map(_.toLong)
      .getOrElse((scala.util.hashing.MurmurHash3.stringHash(specName).toLong ^ run) & 0xffffffffL)
    println(s"[$specName] seed = $s (set with -Dseed=$s)")
    s
  }
  def rng(specName: String): scala.util.Random = new scala.util.Random(seed(specName))

  /** How many random cases to run: the default times -Dscale=K (or env SCALE), e.g. K = 10
    * for a longer soak; K may be fractional (0.1 for a quick smoke run). */
  def cases(default: Int): Int = {
    val k = sys.props.get("scale").orElse(sys.env.get("SCALE")).map(_.toDouble).getOrElse(1.0)
    math.max(1, math.round(default * k).toInt)
  }
}
