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

  /** The depth in `op`s of apply's result for n values: ceil(log2 n). */
  def depth(n: Int): Int = if (n <= 1) 0 else 1 + depth(n - n / 2)
}
