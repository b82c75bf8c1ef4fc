package collide.afu

import java.io.File
import java.nio.file.Files
import org.scalatest.flatspec.AnyFlatSpec

/** generated/default/ is committed; it must be what the generator makes today. */
class GeneratedFreshSpec extends AnyFlatSpec {
  behavior of "generated/default"

  it should "be identical to a fresh run of the generator" in {
    val committed = new File("generated/default")
    val refresh = """sbt "run --preset default""""
    assert(committed.isDirectory, s"generated/default is missing; create it with: $refresh")
    val tmp = Files.createTempDirectory("collide-fresh").toFile
    val fresh = new File(tmp, "default")
    collide.Generate.generate(AfuConfig.default, fresh, split = false, verilog = true, command = refresh)
    def listing(d: File) = d.listFiles().map(_.getName).sorted.toSeq
    assert(listing(fresh) == listing(committed),
      s"files differ: fresh ${listing(fresh)} vs committed ${listing(committed)}; refresh with: $refresh")
    for (name <- listing(fresh)) {
      val a = Files.readAllBytes(new File(fresh, name).toPath)
      val b = Files.readAllBytes(new File(committed, name).toPath)
      assert(java.util.Arrays.equals(a, b), s"generated/default/$name is stale; refresh with: $refresh")
    }
  }
}
