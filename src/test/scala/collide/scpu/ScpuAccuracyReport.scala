package collide.scpu

import scala.util.Random
import collide.fp._
import collide.scpu.model._

/** Accuracy of every preset against ODE's formula in double (OdeReference), on the golden
  * model (bit-exact with the RTL, ScpuSpec). Prints markdown; bench/scpu-accuracy.md holds a
  * committed run.
  *
  *   sbt "Test/runMain collide.scpu.ScpuAccuracyReport [pairsPerSet] [seed]"
  *
  * The reference sees the compute-format inputs (exact in double), so what is measured is the
  * arithmetic, not the rounding of the inputs. Errors are in ulps of the compute format (the
  * precision the result carries; the link format only carries it) at the reference value,
  * and relative (normwise for the 3-vectors). Depth's error is also given in ulps of
  * r1 + r2: depth = (r1 + r2) - d cancels near grazing, so its own ulps overstate.
  */
object ScpuAccuracyReport {
  final class Stat {
    var n = 0; var worst = 0.0; var sum = 0.0
    def add(x: Double): Unit = { n += 1; sum += x; if (x > worst || x.isNaN) worst = x }
    def mean: Double = if (n == 0) 0 else sum / n
    def show(fmt: String): String = s"${fmt.format(worst)} / ${fmt.format(mean)}"
  }

  def ulp(f: FloatFormat, x: Double): Double = {
    val ax = math.abs(x)
    if (ax == 0 || ax < math.pow(2, f.minExp)) math.pow(2, f.minSubExp)
    else math.pow(2, math.getExponent(ax) - f.fracBits)
  }

  final case class Row(cfg: ScpuConfig, pos: Stat, posRel: Stat, nrm: Stat, nrmRel: Stat, nlen: Stat, depth: Stat,
                       depthRs: Stat, contacts: Int, mismatchGrazing: Int, grazingPairs: Int, mismatchAll: Int,
                       kindMismatch: Int, nonFiniteWide: Int, wideHits: Int, mismatchWideBand: Int, mismatchWideOut: Int,
                       badNormalWide: Int, widePairs: Int)

  def measure(cfg: ScpuConfig, n: Int, seed: Long): Row = {
    val f = cfg.format
    val v = new ScpuVectors(cfg)
    val model = ScpuModel(cfg)
    val rng = new Random(seed)
    val pos = new Stat; val posRel = new Stat; val nrm = new Stat; val nrmRel = new Stat; val nlen = new Stat
    val depth = new Stat; val depthRs = new Stat
    var contacts = 0; var mismG = 0; var mismAll = 0; var kindMism = 0
    def d(b: BigInt) = ScpuModel.toDouble(cfg.linkFormat, b)
    def run(p: ScpuPair): (ScpuTrace, OdeContact) = {
      val t = model.trace(p)
      val x = t.inputs.map(ScpuModel.toDouble(f, _))
      (t, OdeReference.collide(V3(x(0), x(1), x(2)), x(3), V3(x(4), x(5), x(6)), x(7)))
    }
    val sets = Seq.fill(n)(v.uniform(rng)) ++ Seq.fill(n)(v.largeSmallGap(rng))
    val grazing = Seq.fill(n)(v.grazing(rng))
    for ((p, isGrazing) <- sets.map(_ -> false) ++ grazing.map(_ -> true)) {
      val (t, ref) = run(p)
      val r = t.result
      if (r.hit != ref.hit) { mismAll += 1; if (isGrazing) mismG += 1 }
      else if (r.kind != ref.kind) kindMism += 1
      else if (r.kind == ContactKind.Contact) {
        contacts += 1
        val gp = Seq(r.px, r.py, r.pz).map(d); val rp = ref.pos.toSeq
        val gn = Seq(r.nx, r.ny, r.nz).map(d); val rn = ref.normal.toSeq
        def normInf(xs: Seq[Double]) = xs.map(math.abs).max
        // Position: normwise (a component near 0 is the difference of p1 and n*k, its own
        // ulps say nothing about the contact point's accuracy).
        pos.add(normInf(gp.zip(rp).map { case (a, b) => a - b }) / ulp(f, normInf(rp)))
        gn.zip(rn).foreach { case (g, e) => nrm.add(math.abs(g - e) / ulp(f, e)) }
        posRel.add(normInf(gp.zip(rp).map { case (a, b) => a - b }) / math.max(normInf(rp), Double.MinPositiveValue))
        nrmRel.add(normInf(gn.zip(rn).map { case (a, b) => a - b }) / math.max(normInf(rn), Double.MinPositiveValue))
        nlen.add(math.abs(math.sqrt(gn.map(x => x * x).sum) - 1) / math.pow(2, -f.fracBits))
        val gd = d(r.depth)
        val rs = ScpuModel.toDouble(f, t.rs.bits)
        // Depth's own ulps only where it does not cancel (depth >= (r1 + r2) / 8).
        if (ref.depth >= rs / 8) depth.add(math.abs(gd - ref.depth) / ulp(f, ref.depth))
        depthRs.add(math.abs(gd - ref.depth) / ulp(f, rs))
      }
    }
    // Across the whole range: non-finite contact fields from finite inputs, decisions vs exact.
    var nonFin = 0; var wideHits = 0; var mismBand = 0; var mismOut = 0; var badN = 0
    val wide = Seq.fill(n)(v.wideRange(rng))
    val rel = ScpuExact.pow2(-f.fracBits).multiply(new java.math.BigDecimal(ScpuBounds.bandUlps(cfg)))
    val abs = ScpuExact.pow2(f.minSubExp + 1)
    for (p <- wide) {
      val t = model.trace(p)
      val r = t.result
      if (r.hit) {
        wideHits += 1
        if (r.fields.exists(b => { val x = d(b); x.isNaN || x.isInfinite })) nonFin += 1
        if (r.kind == ContactKind.Contact) {
          val m = ScpuExact.normSqMinusOne(cfg.linkParams, Seq(r.nx, r.ny, r.nz))
          if (m.forall(x => math.abs(x.doubleValue) / 2 > ScpuBounds.normalUlps(cfg) * math.pow(2, -f.fracBits))) badN += 1
        }
      }
      ScpuExact.decision(cfg.params, t.inputs).foreach { e =>
        if (e.hit != r.hit) { if (e.within(rel, abs)) mismBand += 1 else mismOut += 1 }
      }
    }
    Row(cfg, pos, posRel, nrm, nrmRel, nlen, depth, depthRs, contacts, mismG, grazing.size, mismAll, kindMism, nonFin,
      wideHits, mismBand, mismOut, badN, wide.size)
  }

  def table(rows: Seq[Row], n: Int): String = {
    val sb = new StringBuilder
    sb ++= s"Per preset: $n uniform + $n large-coordinate/small-gap + $n grazing pairs against OdeReference (double),\n"
    sb ++= s"then $n pairs across the whole exponent range against exact arithmetic. Cells: worst / mean.\n\n"
    sb ++= "| preset | latency | pos ulps (normwise) | pos rel | normal ulps | normal rel | \\|n\\|-1 ulps | depth ulps (depth >= (r1+r2)/8) | depth err / ulp(r1+r2) | contacts | decision != double (grazing / all) | kind != double |\n"
    sb ++= "|---|---:|---|---|---|---|---|---|---|---:|---:|---:|\n"
    for (r <- rows) {
      sb ++= s"| ${r.cfg.name} | ${r.cfg.latency} | ${r.pos.show("%.2f")} | ${r.posRel.show("%.1e")} | ${r.nrm.show("%.2f")} | " +
        s"${r.nrmRel.show("%.1e")} | ${r.nlen.show("%.2f")} | ${r.depth.show("%.3g")} | ${r.depthRs.show("%.2f")} | ${r.contacts} | " +
        s"${r.mismatchGrazing} of ${r.grazingPairs} / ${r.mismatchAll} | ${r.kindMismatch} |\n"
    }
    sb ++= "\nWhole exponent range (finite inputs below maxFinite/4; `ScpuVectors.wideRange`):\n\n"
    sb ++= "| preset | hits | hits with a NaN/inf field | decision != exact, within the band / outside | contacts with \\|n\\|-1 beyond the bound |\n|---|---:|---:|---:|---:|\n"
    for (r <- rows) sb ++= s"| ${r.cfg.name} | ${r.wideHits} of ${r.widePairs} | ${r.nonFiniteWide} | ${r.mismatchWideBand} / ${r.mismatchWideOut} | ${r.badNormalWide} |\n"
    sb.result()
  }

  /** One row per preset, machine-readable, for bench/sweep's accuracy-cost tables. */
  def csv(rows: Seq[Row]): String = {
    val stats = Seq[(String, Row => Stat)]("pos_ulps" -> (_.pos), "pos_rel" -> (_.posRel), "normal_ulps" -> (_.nrm),
      "normal_rel" -> (_.nrmRel), "nlen_ulps" -> (_.nlen), "depth_ulps" -> (_.depth), "depth_rs_ulps" -> (_.depthRs))
    val head = Seq("preset", "latency") ++ stats.flatMap { case (k, _) => Seq(s"${k}_worst", s"${k}_mean") } ++
      Seq("contacts", "grazing_pairs", "decision_mismatch_grazing", "decision_mismatch_all", "kind_mismatch",
        "wide_pairs", "wide_hits", "wide_nonfinite_hits", "wide_mismatch_band", "wide_mismatch_outside", "wide_bad_normal")
    val body = rows.map { r =>
      (Seq(r.cfg.name, r.cfg.latency.toString) ++ stats.flatMap { case (_, f) => Seq(f(r).worst.toString, f(r).mean.toString) } ++
        Seq(r.contacts, r.grazingPairs, r.mismatchGrazing, r.mismatchAll, r.kindMismatch, r.widePairs, r.wideHits,
          r.nonFiniteWide, r.mismatchWideBand, r.mismatchWideOut, r.badNormalWide).map(_.toString)).mkString(",")
    }
    (head.mkString(",") +: body).mkString("", "\n", "\n")
  }

  /** args: [pairs] [seed] [--csv FILE] [--configs SPEC,SPEC...] (ScpuConfig.parse specs; default
    * every preset). The markdown report goes to stdout either way. */
  def main(argv: Array[String]): Unit = {
    def opt(name: String, a: Array[String]): (Option[String], Array[String]) = {
      val at = a.indexOf(name)
      if (at < 0) (None, a) else (Some(a.lift(at + 1).getOrElse(sys.error(s"$name: missing value"))), a.patch(at, Nil, 2))
    }
    val (csvFile, a1) = opt("--csv", argv)
    val (specs, args) = opt("--configs", a1)
    val configs = specs.map(_.split(",").toSeq.map(s => ScpuConfig.parse(s.trim) match {
      case Right(c) => c
      case Left(e) => sys.error(s"--configs: $e")
    })).getOrElse(ScpuConfig.all)
    val n = args.headOption.map(_.toInt).getOrElse(10000)
    val seed = args.lift(1).map(_.toLong).getOrElse(20261122L)
    val rows = configs.map { c =>
      val t0 = System.nanoTime()
      val r = measure(c, n, seed)
      System.err.println(f"${c.name}: ${(System.nanoTime() - t0) / 1e9}%.1f s")
      r
    }
    csvFile.foreach(f => java.nio.file.Files.writeString(java.nio.file.Paths.get(f), csv(rows)))
    println(s"<!-- sbt \"Test/runMain collide.scpu.ScpuAccuracyReport $n $seed\" -->")
    println(table(rows, n))
    println("\nConfigurations:\n")
    configs.foreach(c => println(s"- ${c.describe}; operators ${c.operatorCount.toSeq.sorted.map { case (k, v) => s"$k $v" }.mkString(", ")}"))
  }
}
