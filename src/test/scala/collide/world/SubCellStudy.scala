package collide.world

import collide.fp.FloatFormat
import collide.scpu.ScpuConfig
import collide.world.BroadPhaseWorlds._
import collide.world.model._

/** A model study of the next step for the grid (docs/afu.md, "What would make the grid
  * faster"): chunks of a cell twice the needed size whose visits are the needed-size cells
  * ("fine cells") within reach, against today's chunks of one needed-size cell and its 13
  * half-shell neighbours. Today a chunk streams 14 cells' worth of spheres past itself, so
  * about 14 probes a sphere whatever the cell size while a cell fits in a chunk. A coarse
  * cell of 2 x 2 x 2 fine cells needs only its own 8 and the 28 fine cells of its half-shell
  * neighbours that touch it (a face neighbour's 4, an edge neighbour's 2, a corner's 1): 36
  * fine cells for 8 cells' members, 4.5 a member, as long as the coarse cell fits a chunk.
  *
  * Both traversals are counted here the same way, on exact cell occupancy (no hash
  * collisions) and BroadPhaseModel.cycles' accounting (a chunk costs its members, and each
  * visit max(1, its spheres); cells dealt round-robin to the lanes). Not RTL: a sizing study.
  * It checks that the coarse traversal gives each pair once, that every pair passes the box
  * filter, and that it holds every candidate of today's traversal (so every SCPU hit, which
  * BroadPhaseModelSpec proves are candidates).
  *
  *   sbt "Test/runMain collide.world.SubCellStudy [--sizes 1000,4000,16000] [--spheres FILE.csv ...]
  *        [--cell-steps 1|2] [--lanes 16] [--chunk 16]"
  */
object SubCellStudy {
  final case class Work(chunks: Long, lookups: Long, probes: Long, generate: Long, pairs: Set[(Int, Int)])

  private def deal(work: Seq[Long], lanes: Int): Long = {
    val perLane = Array.fill(lanes)(0L)
    work.zipWithIndex.foreach { case (w, c) => perLane(c % lanes) += w }
    perLane.max
  }

  def main(args: Array[String]): Unit = {
    var sizes = Seq(1000, 4000, 16000); var files = Seq.empty[String]; var steps = 1; var lanes = 16; var chunk = 16
    args.sliding(2, 2).foreach {
      case Array("--sizes", v)      => sizes = v.split(',').map(_.trim.toInt).toSeq.filter(_ > 0)
      case Array("--spheres", v)    => files :+= v
      case Array("--cell-steps", v) => steps = v.toInt
      case Array("--lanes", v)      => lanes = v.toInt
      case Array("--chunk", v)      => chunk = v.toInt
      case a => throw new IllegalArgumentException(s"unknown option ${a.mkString(" ")} (expected --sizes, --spheres, --cell-steps, --lanes, --chunk)")
    }
    val rng = new scala.util.Random(1)
    val worlds = sizes.flatMap(n => Seq("uniform" -> uniform(rng, n), "clustered" -> clustered(rng, n, clusters = 1 + n / 200))) ++
      files.map(BroadPhaseCycleReport.readSpheres)
    val model = new BroadPhaseModel(ScpuConfig.fp32, BroadPhaseParams.default.copy(cellSteps = steps, chunk = chunk, bucketsLog2 = 18))
    println(s"lanes $lanes, chunk $chunk, cell steps $steps")
    println("| world | spheres | cell edge | spheres a cell | today: chunks | lookups/sphere | probes/sphere | generate | coarse: chunks | lookups/sphere | probes/sphere | generate | today/coarse | hybrid: chunks | lookups/sphere | probes/sphere | generate | today/hybrid | candidates today | coarse |")
    println("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for ((name, ws) <- worlds) {
      val world = bits(FloatFormat.fp32, ws).toIndexedSeq
      val r = model.run(world)
      val conv = world.map(model.converted)
      val small = world.indices.flatMap(i => r.classes(i) match { case c: SphereClass.Small => Some(i -> c); case _ => None })
      val box = world.indices.map(i => model.boxKey(conv(i), r.level))
      val slack = model.boxSlack(r.level)
      type C = (Long, Long, Long)
      val fine: Map[C, IndexedSeq[Int]] = small.groupBy { case (_, c) => (c.cx, c.cy, c.cz) }.map { case (k, v) => k -> v.map(_._1).sorted }
      val fineOf: Map[Int, SphereClass.Small] = small.toMap
      def occ(c: C) = fine.getOrElse(c, IndexedSeq.empty)
      def add(a: C, o: (Int, Int, Int)): C = (a._1 + o._1, a._2 + o._2, a._3 + o._3)
      def half(v: Long) = Math.floorDiv(v, 2L)
      val coarseCells = small.groupBy { case (_, c) => (half(c.cx), half(c.cy), half(c.cz)) }.map { case (k, v) => k -> v.map(_._1).sorted }

      /** One traversal's counts and pairs; each pair must come out once. */
      final class Tally {
        var chunks, lookups, probes = 0L
        private val out = scala.collection.mutable.ArrayBuffer.empty[(Int, Int)]
        /** Streams cell f past `members`, member i taking sphere e where `takes(i, e)` and the box
          * filter pass; its cost, max(1, the spheres streamed). */
        def visit(f: C, members: Seq[Int])(takes: (Int, Int) => Boolean): Long = {
          val es = occ(f); lookups += 1; probes += es.length
          for (e <- es; i <- members if takes(i, e) && model.boxPass(box(i), box(e), slack)) out += ((math.min(i, e), math.max(i, e)))
          math.max(1, es.length)
        }
        /** Today's chunks of one fine cell: its own cell (j > i) and 13 half-shell neighbours. */
        def fineChunks(cell: C, members: Seq[Int]): Long =
          members.grouped(chunk).map { ch =>
            chunks += 1
            ch.length + BroadPhaseModel.Visits.map(o => visit(add(cell, o), ch)((i, e) => o != BroadPhaseModel.Own || e > i)).sum
          }.sum
        def result(what: String, work: Seq[Long]): Work = {
          val set = out.toSet
          require(set.size == out.length, s"$name: the $what traversal gave ${out.length - set.size} pairs twice")
          Work(chunks, lookups, probes, deal(work, lanes), set)
        }
      }

      // Today: a chunk of one fine cell.
      val today = {
        val t = new Tally
        t.result("today's", fine.toSeq.sortBy(_._2.head).map { case (cell, own) => t.fineChunks(cell, own) })
      }

      // Coarse: a chunk of one coarse cell (2 x 2 x 2 fine cells); its own 8 fine cells (j > i)
      // and, of each half-shell neighbour, the fine cells that touch it.
      val coarse = {
        val t = new Tally
        def layers(base: Long, o: Int): Seq[Long] = o match { case 1 => Seq(2 * base); case -1 => Seq(2 * base + 1); case _ => Seq(2 * base, 2 * base + 1) }
        t.result("coarse", coarseCells.toSeq.sortBy(_._2.head).map { case (cc, own) =>
          own.grouped(chunk).map { ch =>
            t.chunks += 1
            ch.length + (for (o <- BroadPhaseModel.Visits; n = add(cc, o); fx <- layers(n._1, o._1); fy <- layers(n._2, o._2); fz <- layers(n._3, o._3))
              yield t.visit((fx, fy, fz), ch)((i, e) => o != BroadPhaseModel.Own || e > i)).sum
          }.sum
        })
      }
      // Hybrid: a coarse cell that fits a chunk is one chunk; every other is chunked by fine cell
      // as today. A coarse chunk streams the 43 fine cells in some member's own or half-shell
      // neighbourhood (BroadPhaseModel.CoarseVisits), and each member takes a probe only if it
      // owns it (BroadPhaseModel.owns: today's rule, per member), so both kinds of chunk mix with
      // each pair found once, by its owner: the golden model's coarseChunks, here without hashing.
      val hybrid = {
        val t = new Tally
        t.result("hybrid", coarseCells.toSeq.sortBy(_._2.head).flatMap { case (cc, own) =>
          if (own.length <= chunk) {
            t.chunks += 1
            Seq(own.length + BroadPhaseModel.CoarseVisits.map { d =>
              val f = (2 * cc._1 + d._1, 2 * cc._2 + d._2, 2 * cc._3 + d._3)
              val visited = SphereClass.Small(f._1, f._2, f._3)
              t.visit(f, own)((i, e) => BroadPhaseModel.owns(fineOf(i), visited, i, e))
            }.sum)
          } else {
            // Today's chunks for each of its fine cells, in order of their first member.
            own.groupBy(i => { val c = fineOf(i); (c.cx, c.cy, c.cz) }).toSeq.sortBy(_._2.head).map { case (cell, mine) => t.fineChunks(cell, mine) }
          }
        })
      }
      require(hybrid.pairs == today.pairs, s"$name: the hybrid traversal's candidates differ from today's " +
        s"(${(today.pairs -- hybrid.pairs).size} missing, ${(hybrid.pairs -- today.pairs).size} more)")
      val missing = today.pairs -- coarse.pairs
      require(missing.isEmpty, s"$name: the coarse traversal misses ${missing.size} of today's candidates, e.g. ${missing.head}")
      require(today.pairs == r.candidates.take(r.stats.gridCandidates.toInt).toSet, s"$name: today's traversal is not the model's")
      val n = ws.length.toDouble
      def f(w: Work) = f"${w.chunks} | ${w.lookups / n}%.1f | ${w.probes / n}%.1f | ${w.generate}"
      println(f"| $name | ${ws.length} | ${BroadPhaseParams.edge(r.level)}%g | ${small.length.toDouble / fine.size}%.2f | ${f(today)} | ${f(coarse)} | " +
        f"${today.generate.toDouble / coarse.generate}%.2f | ${f(hybrid)} | ${today.generate.toDouble / hybrid.generate}%.2f | ${today.pairs.size} | ${coarse.pairs.size} |")
    }
  }
}
