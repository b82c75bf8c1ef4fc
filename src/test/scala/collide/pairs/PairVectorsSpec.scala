package collide.pairs

import org.scalatest.flatspec.AnyFlatSpec

/** The committed vectors of the pair kinds (read by test/test_pair_kinds.cpp) are what the
  * golden models write today: a change to a model or its stimulus must regenerate them. */
class PairVectorsSpec extends AnyFlatSpec {
  behavior of "PairVectorsWriter"

  for (kind <- PairVectorsWriter.kinds; (name, cfg) <- PairVectorsWriter.formats)
    it should s"have written the committed ${kind.name} $name vectors" in {
      val path = java.nio.file.Paths.get(PairVectorsWriter.path(kind.name, name))
      val regen = "run tools/sbt \"Test/runMain collide.pairs.PairVectorsWriter\" and commit it"
      assert(java.nio.file.Files.exists(path), s"$path is missing: $regen")
      val committed = new String(java.nio.file.Files.readAllBytes(path), "UTF-8")
      assert(committed == PairVectorsWriter.text(kind, cfg), s"$path is stale: $regen")
    }
}
