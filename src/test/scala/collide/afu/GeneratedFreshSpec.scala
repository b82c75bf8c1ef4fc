package collide.afu

import java.io.File
import java.nio.file.Files
import org.scalatest.flatspec.AnyFlatSpec

/** generated/default/, generated/world/, generated/cosim/, generated/world_fit/ and the contract headers are committed; they must be what the
  * generator makes today. */
class GeneratedFreshSpec extends AnyFlatSpec {
  behavior of "generated/"

  it should "hold the contract headers the generator writes today" in {
    val refresh = """sbt "run --preset default""""
    val tmp = Files.createTempDirectory("collide-contract").toFile
    for (f <- collide.Generate.writeContract(tmp)) {
      val committed = new File("generated", f.getName)
      assert(committed.isFile, s"generated/${f.getName} is missing; create it with: $refresh")
      assert(java.util.Arrays.equals(Files.readAllBytes(f.toPath), Files.readAllBytes(committed.toPath)),
        s"generated/${f.getName} is stale; refresh with: $refresh")
    }
  }

  // The AFUs the host builds: the default one, the world preset (world mode's CLI test), the
  // default for fast co-simulation (its SCPUs the C++ model) and world-fit (its results).
  for (cfg <- Seq(AfuConfig.default, AfuConfig.world, AfuConfig.cosim, AfuConfig.worldFit)) {
    val dir = s"generated/${cfg.id}"
    it should s"hold $dir identical to a fresh run of the generator" in {
      val committed = new File(dir)
      val refresh = s"""sbt "run --preset ${cfg.name}""""
      assert(committed.isDirectory, s"$dir is missing; create it with: $refresh")
      val tmp = Files.createTempDirectory("collide-fresh").toFile
      val fresh = new File(tmp, cfg.name)
      collide.Generate.generate(cfg, fresh, split = false, verilog = true, command = refresh)
      // timing.json is the timing proxy's account of this Verilog (bench/area/reached_clock.py),
      // not the generator's output: the host build checks that it names this Verilog.
      def listing(d: File) = d.listFiles().map(_.getName).filterNot(_ == "timing.json").sorted.toSeq
      assert(listing(fresh) == listing(committed),
        s"files differ: fresh ${listing(fresh)} vs committed ${listing(committed)}; refresh with: $refresh")
      for (name <- listing(fresh)) {
        val a = Files.readAllBytes(new File(fresh, name).toPath)
        val b = Files.readAllBytes(new File(committed, name).toPath)
        assert(java.util.Arrays.equals(a, b), s"$dir/$name is stale; refresh with: $refresh")
      }
    }
  }
}
