package collide.testutil

/** Seeds for randomized specs: printed, and settable with -Dseed=N (or env SEED) so any
  * failure can be replayed: `sbt -Dseed=1234 "testOnly collide.fp.FpAddSpec"`.
  */
object Seeds {
  def seed(specName: String): Long = {
    val s = sys.props.get("seed").orElse(sys.env.get("SEED")).map(_.toLong)
      .getOrElse(scala.util.hashing.MurmurHash3.stringHash(specName).toLong & 0xffffffffL)
    println(s"[$specName] seed = $s (set with -Dseed=$s)")
    s
  }
  def rng(specName: String): scala.util.Random = new scala.util.Random(seed(specName))

  /** How many random cases to run: -Dcases=N scales the default, e.g. for a longer soak. */
  def cases(default: Int): Int = sys.props.get("cases").map(_.toInt).getOrElse(default)
}
