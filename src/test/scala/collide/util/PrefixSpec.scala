package collide.util

import org.scalatest.flatspec.AnyFlatSpec

/** Prefix's order and depth (pure Scala: the hardware users are checked by their own specs). */
class PrefixSpec extends AnyFlatSpec {
  behavior of "Prefix"

  it should "give scanLeft's inclusive prefixes for every length up to 70, keeping the order of a non-commutative op" in {
    for (n <- 0 to 70) {
      val xs = (0 until n).map(i => s"<$i>")
      assert(Prefix(xs)(_ + _) == xs.scanLeft("")(_ + _).tail, s"n = $n")
      val ns = (0 until n).map(i => (i * 7919) % 101)
      assert(Prefix(ns)(_ + _) == ns.scanLeft(0)(_ + _).tail, s"n = $n")
    }
  }

  it should "combine in ceil(log2 n) levels rather than n - 1" in {
    // Each value carries the levels of ops behind it.
    for (n <- 1 to 70) {
      val levels = Prefix(Seq.fill(n)(0))((a, b) => math.max(a, b) + 1).max
      assert(levels == Prefix.depth(n) && levels == (if (n == 1) 0 else 32 - Integer.numberOfLeadingZeros(n - 1)), s"n = $n")
    }
  }

  behavior of "Tree.reduce"

  it should "equal reduce for every length up to 70, in ceil(log2 n) levels, keeping the order" in {
    for (n <- 1 to 70) {
      val xs = (0 until n).map(i => s"<$i>")
      assert(Tree.reduce(xs)(_ + _) == xs.reduce(_ + _), s"n = $n")
      assert(Tree.reduce(Seq.fill(n)(0))((a, b) => math.max(a, b) + 1) == Prefix.depth(n), s"n = $n")
    }
    assertThrows[IllegalArgumentException](Tree.reduce(Seq.empty[Int])(_ + _))
  }
}
