package collide.afu

import java.nio.file.{Files, Paths}

/** The sphere table's RAM against SCPU count, replicated and banked (no hardware built: the
  * bits and M20K blocks come from the same PucParams the generator builds from).
  * `tools/sbt "Test/runMain collide.afu.SphereRamReport --out bench/results/banked/ram.csv"` */
object SphereRamReport {
  val counts: Seq[Int] = Seq(1, 2, 4, 8, 16, 32, 64)
  val sizes: Seq[Int] = Seq(1024, 4096, 65536)

  def rows: Seq[Seq[Any]] =
    for (spheres <- sizes; n <- counts; ram <- Seq(SphereRamPorts.Replicated, SphereRamPorts.Banked())) yield {
      val p = AfuConfig.default.copy(scpus = n, maxSpheres = spheres, ramPorts = ram).puc
      Seq(spheres, n, if (ram == SphereRamPorts.Replicated) "replicated" else "banked", p.ramCopies, p.banks, p.ramBits,
        p.ramM20k, f"${100.0 * p.ramM20k / M20k.deviceBlocks}%.1f", p.ramM20k <= M20k.deviceBlocks)
    }

  def main(args: Array[String]): Unit = {
    val out = args.sliding(2, 2).collectFirst { case Array("--out", f) => f }
    val text = ("max_spheres,scpus,ram_ports,copies,banks,sphere_table_bits,m20k,m20k_pct_5sgxea7,fits" +: rows.map(_.mkString(",")))
      .mkString("", "\n", "\n")
    out match {
      case Some(f) => Option(Paths.get(f).getParent).foreach(Files.createDirectories(_)); Files.write(Paths.get(f), text.getBytes("UTF-8"))
        println(s"wrote ${rows.size} rows to $f")
      case None => print(text)
    }
  }
}
