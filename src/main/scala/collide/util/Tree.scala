package collide.util

/** A reduction in ceil(log2 n) levels of `op` instead of Scala's reduce, which chains n - 1 of
  * them in series (synthesis keeps the chain): for an associative `op`, the left operand is
  * always the earlier part, so ties resolve as a left-to-right reduce would.
  */
object Tree {
  def reduce[T](xs: Seq[T])(op: (T, T) => T): T = {
    require(xs.nonEmpty, "Tree.reduce of nothing")
    if (xs.length == 1) xs.head
    else {
      val (l, r) = xs.splitAt(xs.length / 2)
      op(reduce(l)(op), reduce(r)(op))
    }
  }
}
