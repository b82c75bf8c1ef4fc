package collide.util

import chisel3.RawModule
import circt.stage.ChiselStage

/** Emits SystemVerilog that Verilator and Yosys 0.23 both read (shared/NOTES.md: Yosys needs
  * firtool's output without local variables, packed arrays or always_comb).
  */
object Emit {
  val loweringOptions = "disallowLocalVariables,disallowPackedArrays,noAlwaysComb"

  val firtoolOpts: Array[String] = Array(
    s"--lowering-options=$loweringOptions",
    "--disable-all-randomization",
    "--strip-debug-info"
  )

  /** The design as one SystemVerilog string. */
  def systemVerilog(gen: => RawModule): String =
    ChiselStage.emitSystemVerilog(gen, Array.empty, firtoolOpts)

  /** Writes the design into `dir` as one file `<top>.sv`; returns the file. */
  def toFile(gen: => RawModule, dir: java.io.File, top: String): java.io.File = {
    dir.mkdirs()
    val f = new java.io.File(dir, s"$top.sv")
    val w = new java.io.PrintWriter(f)
    try w.write(systemVerilog(gen)) finally w.close()
    f
  }
}
