package collide.testutil

/** Tag for slow end-to-end cases, excluded from the default test run (`-l collide.Slow`). */
object Slow extends org.scalatest.Tag("collide.Slow")
