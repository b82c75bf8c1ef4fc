package collide.formal

import chisel3._
import chisel3.util._
import chiseltest._
import chiseltest.formal._
import org.scalatest.flatspec.AnyFlatSpec
import collide.afu.{PucParams, RecordLayout}
import collide.testutil.Slow

/** What a formal wrapper is built to check (docs/formal.md):
  *  - Prove: its assertions hold at every cycle up to the bound;
  *  - Reach: it asserts that its finish state is never reached, so the bounded check must FAIL,
  *    and its counterexample is a witness that the block gets there. chiseltest 6.0.0's
  *    bounded check ignores `cover` (only assertions become bad states), so this stands in
  *    for the covers, which the wrappers keep for tools that check them;
  *  - SeededBug: a proof with one mistake planted in the wrapper (a dropped valid, a double
  *    count), which must FAIL: the properties are written to catch it. */
sealed trait Check
object Check {
  case object Prove extends Check
  case object Reach extends Check
  case object SeededBug extends Check
}

/** Environment rules and checks shared by the wrappers. Assumptions and assertions are off in
  * the reset cycle (Chisel guards them with reset). */
object FormalEnv {
  /** The producer of `d` (the environment) holds valid and bits from the cycle it offers until
    * the cycle of fire. */
  def producerHolds[T <: Data](d: DecoupledIO[T]): Unit = {
    val waiting = RegNext(d.valid && !d.ready, false.B)
    val was = RegNext(d.bits)
    when(waiting) { assume(d.valid, "producer holds valid"); assume(d.bits.asUInt === was.asUInt, "producer holds bits") }
  }
  /** `x` keeps the value it has in the first cycle after reset. */
  def stable(x: Data): Unit = {
    val first = RegInit(true.B); first := false.B
    val was = RegNext(x)
    when(!first) { assume(x.asUInt === was.asUInt, "stable input") }
  }
  /** A counter of `inc` per cycle, `w` bits. */
  def counter(inc: UInt, w: Int): UInt = {
    val c = RegInit(0.U(w.W)); c := c + inc; c
  }
  /** Cycles since reset, saturating. */
  def cycles(w: Int = 8): UInt = {
    val c = RegInit(0.U(w.W)); when(!c.andR) { c := c + 1.U }; c
  }
  /** The finish check: in Prove mode nothing; in Reach mode assert that `goal` never holds (the
    * check must then fail); `cover` either way, for tools that check covers. */
  def finish(check: Check, goal: Bool, what: String): Unit = {
    cover(goal, what)
    if (check == Check.Reach) assert(!goal, s"reached: $what")
  }
}

/** The small parameterizations the wrappers are checked at (the specs and EmitFormal share them). */
object FormalParams {
  /** Two SCPUs on a 16-bit link: 16-pair lines, two lanes. */
  val dispatcher = PucParams(scpus = 2, linkWidth = 16, scpuTagBits = 24, scpuLatency = 1, maxSpheres = 64,
    maxReads = 2, maxWrites = 2, tagBits = 1, name = "_formal2")
  /** Two fp32 SCPUs with full records: two records a line (the collector and the packer). */
  val records = PucParams(scpus = 2, linkWidth = 32, scpuTagBits = 24, scpuLatency = 1, maxSpheres = 64,
    maxReads = 2, maxWrites = 2, tagBits = 1, records = RecordLayout.Full, name = "_formal")
  /** One SCPU, two read tags: a 2-line pair buffer and an 8-line sphere table. */
  val reader = PucParams(scpus = 1, linkWidth = 16, scpuTagBits = 24, scpuLatency = 1, maxSpheres = 64,
    maxReads = 2, maxWrites = 2, tagBits = 1, name = "_formal")
}

object FormalSpecKit {
  /** The engine (FORMAL_ENGINE; docs/formal.md): Yices 2 unless named. */
  val engineName = sys.env.getOrElse("FORMAL_ENGINE", "yices2")
  val engine = chiseltest.formal.backends.Engines.byName(engineName)
  private def version(cmd: String, hint: String): Either[String, String] =
    scala.util.Try(scala.sys.process.Process(Seq(cmd, "--version")).!!.trim).toEither.left
      .map(e => s"$cmd not found on PATH (${e.getMessage}): $hint")
  /** The engine's solver, checked once before the first check so that a missing one fails the
    * spec at once with the reason. An old z3 is refused too: Debian 12's 4.8.12 takes minutes to
    * read these blocks' encoding before the first step. */
  lazy val solverReady: Either[String, String] = engineName match {
    case "yices2" => version("yices-smt2", "run tools/setup.sh, which puts it in tools/.cache/smt")
    case "z3" => version("z3", "FORMAL_ENGINE=z3 needs z3 4.13 or later on PATH").flatMap { v =>
      val ok = """Z3 version (\d+)\.(\d+)""".r.findFirstMatchIn(v).exists { m =>
        val (major, minor) = (m.group(1).toInt, m.group(2).toInt)
        major > 4 || (major == 4 && minor >= 13)
      }
      if (ok) Right(v) else Left(s"$v: FORMAL_ENGINE=z3 needs z3 4.13 or later on PATH")
    }
    case _ => Right(engineName)
  }
  /** A spec's bound: `default`, or FORMAL_DEPTH_<BLOCK> from the environment (deeper runs by hand). */
  def depth(block: String, default: Int): Int =
    sys.env.get(s"FORMAL_DEPTH_${block.toUpperCase}").map(_.toInt).getOrElse(default)
}

/** Helpers for the formal specs: each check timed and reported in seconds. */
trait FormalSpecKit extends AnyFlatSpec with ChiselScalatestTester with Formal {
  private def timed[A](what: String)(body: => A): A = {
    FormalSpecKit.solverReady.left.foreach(why => fail(why))
    val t0 = System.nanoTime()
    val a = body
    println(f"[formal] $what: ${(System.nanoTime() - t0) / 1e9}%.1f s")
    a
  }
  /** Every assertion holds for `depth` cycles after reset. */
  private def annos(depth: Int) = Seq(BoundedCheck(depth), FormalSpecKit.engine)
  def prove[T <: Module](what: String, depth: Int)(gen: => T): Unit =
    timed(s"$what, proven to depth $depth")(verify(gen, annos(depth)))
  /** One proof as two cases: to `quick` cycles in the suite and to `full` tagged Slow, where the
    * full bound takes minutes (docs/formal.md). */
  def provenQuickAndSlow[T <: Module](should: String, what: String, quick: Int, full: Int)(gen: => T): Unit = {
    it should s"$should, for $quick cycles" in { prove(what, quick)(gen) }
    it should s"$should, for $full cycles" taggedAs Slow in { prove(what, full)(gen) }
  }
  /** The check fails within `depth` cycles (a witness for Reach, a caught bug for SeededBug);
    * returns the exception's message (the step at which it failed). */
  def refute[T <: Module](what: String, depth: Int)(gen: => T): String =
    timed(s"$what, refuted within depth $depth") {
      val e = intercept[FailedBoundedCheckException](verify(gen, annos(depth)))
      println(s"[formal]   ${e.getMessage}")
      e.getMessage
    }
}
