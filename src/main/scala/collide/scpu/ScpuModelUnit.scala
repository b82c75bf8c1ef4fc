package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp.{FloatFormat, RootAlgorithm, RoundingMode}

/** How an AFU's SCPUs are built ("how it is built", apart from what they compute): as RTL, or
  * for simulation only as [[ScpuModelUnit]], the C++ SCPU model behind a pipeline of the SCPU's
  * latency (docs/afu.md, "A faster co-simulation").
  */
sealed trait ScpuImpl { def name: String }
object ScpuImpl {
  case object Rtl extends ScpuImpl { val name = "rtl" }
  case object Model extends ScpuImpl { val name = "model" }
  val all: Seq[ScpuImpl] = Seq(Rtl, Model)
  def parse(s: String): Either[String, ScpuImpl] =
    all.find(_.name == s.trim).toRight(s"SCPU implementation '$s': expected ${all.map(_.name).mkString(" or ")}")

  /** Why the host's C++ SCPU model (host/scpu/scpu_model.hpp) cannot stand in for `cfg`, if it
    * cannot: it reproduces the golden model bit for bit only where every operator is one correct
    * rounding (RNE, subnormals kept, digit-recurrence roots, no rsqrt) of a format binary64
    * emulates exactly (binary64 itself, or 2p + 2 <= 53). The C++ checks the same rule against
    * the golden vectors (ScpuModelCpp.*). */
  def modelRefusal(cfg: ScpuConfig): Option[String] = {
    val f = cfg.format
    if (cfg.rounding != RoundingMode.RNE) Some(s"it rounds ${cfg.rounding}, the model only to nearest even")
    else if (!cfg.subnormals) Some("it flushes subnormals, the model keeps them")
    else if (cfg.distance == DistanceMethod.Rsqrt) Some("rsqrt(d2) is one rounding of 1/sqrt(x), which binary64 cannot reproduce everywhere")
    else if (cfg.sqrtAlg != RootAlgorithm.DigitRecurrence || cfg.recipAlg != RootAlgorithm.DigitRecurrence)
      Some("its roots are not correctly rounded (digit recurrence), which the model's are")
    else if (f != FloatFormat.fp64 && 2 * f.sigBits + 2 > 53)
      Some(s"binary64 does not emulate ${f.name} exactly (needs 2p + 2 <= 53 significand bits)")
    else None
  }
}

/** The SCPU for simulation only: the same ports and handshake as [[Scpu]] (a pipeline of
  * `cfg.latency` stages that all advance when the output is free or taken), whose stage 0 gets
  * its result from the C++ SCPU model through DPI-C (`collide_scpu_model`, host/driver/
  * scpu_model_dpi.cpp) instead of from the datapath. A black box to firtool: its Verilog is
  * [[ScpuModelUnit.verilog]], which Generate writes beside the AFU's. Cycle for cycle the RTL's timing, bit for
  * bit its results (the model is the golden model's, checked against its vectors); a
  * co-simulation then evaluates no floating-point logic. Not synthesizable.
  *
  * @param unitName the module name (it must carry the AFU's id, so two configurations never
  *                 define it differently)
  */
class ScpuModelUnit(val cfg: ScpuConfig, unitName: String) extends BlackBox {
  for (why <- ScpuImpl.modelRefusal(cfg)) require(false, s"SCPU ${cfg.name} cannot be simulated by the C++ model: $why")
  val io = IO(new Bundle {
    val clock = Input(Clock())
    val reset = Input(Reset())
    val in    = Flipped(Decoupled(new ScpuIn(cfg.linkWidth, cfg.tagBits)))
    val out   = Decoupled(new ScpuOut(cfg.linkWidth, cfg.tagBits))
  })
  override def desiredName = unitName
}

object ScpuModelUnit {
  /** The module's name in an AFU of id `afuId`: it carries the id, so two configurations never
    * define it differently. */
  def moduleName(afuId: String): String = s"ScpuModel_$afuId"

  /** Its Verilog (Generate writes it beside the AFU's): the pipeline and the DPI-C import. */
  def verilog(cfg: ScpuConfig, unitName: String): String = {
    val w = cfg.linkWidth
    val t = cfg.tagBits
    val l = cfg.latency
    val values = Seq("px", "py", "pz", "nx", "ny", "nz", "depth", "d", "nw")
    val ins = Seq("x1", "y1", "z1", "r1", "x2", "y2", "z2", "r2")
    // host/scpu/scpu_arith.hpp's DistanceMethod: 0 sqrt then recip, 2 robust
    val distance = if (cfg.distance == DistanceMethod.Robust) 2 else 0
    val resultBits = 1 + 2 + values.size * w + 1 + collide.fp.FpFlags.width + t
    val idxBits = math.max(1, log2Ceil(l))
    s"""// The SCPU ${cfg.name} for simulation only: a pipeline of its latency ($l) around the C++
       |// SCPU model (DPI-C), cycle for cycle the RTL's handshake, bit for bit its results.
       |module $unitName(
       |  input clock, input reset,
       |  output in_ready, input in_valid,
       |${ins.map(n => s"  input [${w - 1}:0] in_bits_$n,").mkString("\n")}
       |  input [${t - 1}:0] in_bits_tag,
       |  input out_ready, output out_valid,
       |  output out_bits_hit, output [1:0] out_bits_kind,
       |${values.map(n => s"  output [${w - 1}:0] out_bits_$n,").mkString("\n")}
       |  output out_bits_nonFinite, output [${collide.fp.FpFlags.width - 1}:0] out_bits_flags,
       |  output [${t - 1}:0] out_bits_tag);
       |  import "DPI-C" function void collide_scpu_model(
       |    input int compute_exp, input int compute_sig, input int link_exp, input int link_sig, input int distance,
       |    ${ins.map(n => s"input longint $n").mkString(", ")},
       |    ${values.map(n => s"output longint $n").mkString(", ")}, output int info);
       |  // A ring of its latency: every stage advances together (en), so the slot written now is
       |  // the one whose result leaves now, $l cycles after it entered; nothing is shifted.
       |  // valid_q is one vector, cleared whole at reset (Verilator refuses a delayed reset loop
       |  // over more than 64 slots of an unpacked array).
       |  reg [${l - 1}:0] valid_q;
       |  reg [${resultBits - 1}:0] data_q [0:${l - 1}];
       |  reg [${idxBits - 1}:0] at;
       |  wire en = !valid_q[at] || out_ready;
       |  assign in_ready = en;
       |  longint ${values.map(n => s"r_$n").mkString(", ")};
       |  int info;
       |  always @(posedge clock) begin
       |    if (reset) begin
       |      valid_q <= ${l}'d0;
       |      at <= ${idxBits}'d0;
       |    end else if (en) begin
       |      if (in_valid) begin
       |        collide_scpu_model(${cfg.format.expBits}, ${cfg.format.sigBits}, ${cfg.linkFormat.expBits}, ${cfg.linkFormat.sigBits}, $distance,
       |          ${ins.map(n => s"64'(in_bits_$n)").mkString(", ")},
       |          ${values.map(n => s"r_$n").mkString(", ")}, info);
       |        data_q[at] <= {info[0], info[2:1], ${values.map(n => s"r_$n[${w - 1}:0]").mkString(", ")}, info[3], info[${8 + collide.fp.FpFlags.width - 1}:8], in_bits_tag};
       |      end
       |      valid_q[at] <= in_valid;
       |      at <= at == ${idxBits}'d${l - 1} ? ${idxBits}'d0 : at + ${idxBits}'d1;
       |    end
       |  end
       |  assign out_valid = valid_q[at];
       |  assign {out_bits_hit, out_bits_kind, ${values.map(n => s"out_bits_$n").mkString(", ")}, out_bits_nonFinite, out_bits_flags, out_bits_tag} = data_q[at];
       |endmodule
       |""".stripMargin
  }
}
