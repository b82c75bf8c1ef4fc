package collide.formal

import chisel3._
import chisel3.util.HasBlackBoxInline

/** The reset of a formal top: high in the first cycle only (an initial value, which the
  * formal flow honours), as chiseltest's bounded check and a real reset do. */
class FormalInitReset extends BlackBox with HasBlackBoxInline {
  val io = IO(new Bundle { val clock = Input(Clock()); val reset = Output(Bool()) })
  setInline("FormalInitReset.sv",
    """module FormalInitReset(input clock, output reset);
      |  reg r = 1'b1;
      |  always @(posedge clock) r <= 1'b0;
      |  assign reset = r;
      |endmodule
      |""".stripMargin)
}

/** A wrapper with its reset made by FormalInitReset and its io left free (the solver's). */
class FormalTop[T <: Module { val io: Record }](gen: => T, name: String) extends RawModule {
  override def desiredName = s"FormalTop_$name"
  val clock = IO(Input(Clock()))
  private val init = Module(new FormalInitReset)
  init.io.clock := clock
  private val inner = withClockAndReset(clock, init.io.reset) { Module(gen) }
  val io = IO(chiselTypeOf(inner.io))
  io <> inner.io
}

/** Writes a formal wrapper's SystemVerilog (its assert/assume as SVA) for SymbiYosys. */
object EmitFormal extends App {
  /** Yosys's open-source Verilog front end reads immediate assertions in a clocked always block,
    * not SVA's concurrent `assert property (@(posedge clock) e)`: the same check, sampled at the
    * same edge, so firtool's SVA is rewritten to it (labels and $error actions dropped). */
  def immediate(sv: String): String = {
    val prop = """(?s)(?:\w+:\s*)?(assert|assume|cover) property \(@\(posedge (\w+)\)\s*([^;]*?)\)\s*(?:else \$error\("(?:[^"\\]|\\.)*"\))?;""".r
    // (the file list firtool appends after the blackbox's source is not Verilog)
    val body = sv.split("""// ----- 8< ----- FILE "firrtl_black_box_resource_files.f"""").head
    prop.replaceAllIn(body, m => java.util.regex.Matcher.quoteReplacement(s"always @(posedge ${m.group(2)}) ${m.group(1)}(${m.group(3)});"))
  }
  val out = new java.io.File(args.headOption.getOrElse("build/formal"))
  out.mkdirs()
  def emit[T <: Module { val io: Record }](name: String, gen: => T): Unit = {
    val sv = circt.stage.ChiselStage.emitSystemVerilog(new FormalTop(gen, name), Array.empty,
      Array("-disable-all-randomization", "-strip-debug-info", "--emit-chisel-asserts-as-sva",
        "--lowering-options=disallowLocalVariables,disallowPackedArrays,noAlwaysComb"))
    val f = new java.io.File(out, s"$name.sv"); val w = new java.io.PrintWriter(f); w.write(EmitFormal.immediate(sv)); w.close()
    println(s"wrote $f")
  }
  emit("TagPool", new TagPoolFormal(4, 2))
  emit("TagPool_bug", new TagPoolFormal(4, 2, Check.SeededBug))
  emit("PairDispatcher", new PairDispatcherFormal(FormalParams.dispatcher))
  emit("PairDispatcher_bug", new PairDispatcherFormal(FormalParams.dispatcher, Check.SeededBug))
  emit("ContactPacker", new ContactPackerFormal(FormalParams.records))
  emit("ContactPacker_bug", new ContactPackerFormal(FormalParams.records, Check.SeededBug))
  emit("ReadEngine", new ReadEngineFormal(FormalParams.reader))
  emit("ReadEngine_bug", new ReadEngineFormal(FormalParams.reader, Check.SeededBug))
}
