package collide.pairs

import org.scalatest.flatspec.AnyFlatSpec

/** The committed sphere/plane vectors (read by test/test_pair_kinds.cpp) are what the golden
  * model writes today: a change to the model or the stimulus must regenerate them. */
class SpherePlaneVectorsSpec extends AnyFlatSpec {
  behavior of "SpherePlaneVectorsWriter"

  for ((name, cfg) <- SpherePlaneVectorsWriter.configs.toSeq.sortBy(_._1))
    it should s"have written the committed $name vectors" in {
      val path = java.nio.file.Paths.get(SpherePlaneVectorsWriter.path(name))
      assert(java.nio.file.Files.exists(path), s"$path is missing: run tools/sbt \"Test/runMain collide.pairs.SpherePlaneVectorsWriter\"")
      val committed = new String(java.nio.file.Files.readAllBytes(path), "UTF-8")
      assert(committed == SpherePlaneVectorsWriter.text(cfg),
        s"$path is stale: run tools/sbt \"Test/runMain collide.pairs.SpherePlaneVectorsWriter\" and commit it")
    }
}
