package collide.util

/** Inclusive prefix combinations in log2(n) levels of `op` (Sklansky's construction):
  * out(i) = xs(0) op xs(1) op ... op xs(i), for an associative `op` (order kept: the left
  * operand is always the earlier part). A Scala scanLeft of hardware values chains n ops in
  * series, and synthesis keeps an adder chain as it is written: a word of 32 counters summed
  * that way was the broad phase's slowest path (docs/afu.md, "Timing").
  */
object Prefix {
  def apply[T](xs: Seq[T])(op: (T, T) => T): Seq[T] =
    if (xs.length <= 1) xs
    else {
      val (l, r) = xs.splitAt(xs.length / 2)
      val pl = apply(l)(op)
      pl ++ apply(r)(op).map(op(pl.last, _))
    }

  /** Inclusive prefix combinations as Kogge and Stone lay them out: log2(n) levels, each
    * level's results passed through `between` (a register, so a pipeline does one level a
    * cycle) before the next level reads them. */
  def levels[T](xs: Seq[T], between: Seq[T] => Seq[T])(op: (T, T) => T): Seq[T] = {
    var cur = xs
    var d = 1
    while (d < xs.length) {
      val prev = cur
      cur = between(prev.indices.map(i => if (i >= d) op(prev(i - d), prev(i)) else prev(i)))
      d *= 2
    }
    cur
  }
  /** Levels of [[levels]] for n values: ceil(log2 n). */
  def levelCount(n: Int): Int = { var d = 1; var l = 0; while (d < n) { d *= 2; l += 1 }; l }

  /** The depth in `op`s of apply's result for n values: ceil(log2 n). */
  def depth(n: Int): Int = if (n <= 1) 0 else 1 + depth(n - n / 2)
}
