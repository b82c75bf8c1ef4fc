package collide.fp.report

import java.nio.file.{Files, Paths}
import chisel3._
import chisel3.util._
import collide.fp._

/** One FP operator between registers: its operands and its result each pass a register, so a
  * timing analysis or a placer sees the operator's own paths and nothing of the pins (the
  * ECP5 flow, bench/area/pnr_ecp5.py, and the proxy, bench/area/afu_timing.py, time it). */
class TimedOperator(op: String, p: FpParams, latency: Int, family: FpgaFamily,
                    alg: RootAlgorithm = RootAlgorithm.DigitRecurrence) extends Module {
  private val w = p.width
  val io = IO(new Bundle {
    val a   = Input(UInt(w.W))
    val b   = Input(UInt(w.W))
    val sub = Input(Bool())
    val rm  = Input(UInt(3.W))
    val out = Output(UInt(w.W))
    val flags = Output(UInt(FpFlags.width.W))
  })
  override def desiredName = s"Timed_${OperatorGen.moduleName(op, p, latency, family)}"
  private val a = RegNext(io.a); private val b = RegNext(io.b)
  private val sub = RegNext(io.sub); private val rm = RegNext(io.rm)
  private val res: FpOut = op match {
    case "add" =>
      val u = Module(new FpAdd(p, latency, family))
      u.io.en := true.B; u.io.in.valid := true.B
      u.io.in.bits.a := a; u.io.in.bits.b := b; u.io.in.bits.subtract := sub; u.io.in.bits.rm := rm
      u.io.out.bits
    case "mul" =>
      val u = Module(new FpMul(p, latency, family))
      u.io.en := true.B; u.io.in.valid := true.B
      u.io.in.bits.a := a; u.io.in.bits.b := b; u.io.in.bits.rm := rm
      u.io.out.bits
    case root =>
      val u = Module(root match {
        case "sqrt"  => new FpSqrt(p, alg, latency)
        case "recip" => new FpRecip(p, alg, latency)
        case _       => new FpRsqrt(p, alg, latency)
      })
      u.io.en := true.B; u.io.in.valid := true.B
      u.io.in.bits.a := a; u.io.in.bits.rm := rm
      u.io.out.bits
  }
  io.out   := RegNext(res.bits)
  io.flags := RegNext(res.flags)
}

/** Writes one operator between registers as SystemVerilog:
  *
  *   sbt "runMain collide.fp.report.OperatorGen --op add --format fp16 --latency 3 --out DIR"
  *   sbt "runMain collide.fp.report.OperatorGen --op mul --format fp32 --mhz 200 --family ecp5 --out DIR"
  *
  * With --mhz the latency is the smallest whose estimated stages fit that clock on the family
  * (FpAdd.latencyFor, FpMul.latencyFor). Prints the file, the top module and the latency. */
object OperatorGen {
  final case class Opts(op: String = "add", format: String = "fp32", subnormals: Boolean = true,
                        latency: Option[Int] = None, mhz: Option[Double] = None,
                        family: String = FpgaFamily.default.name, out: String = "build/operators")

  val ops: Seq[String] = Seq("add", "mul", "sqrt", "recip", "rsqrt")
  private def rootOp(op: String): Option[RootOp] = RootOp.all.find(_.name == op)

  def moduleName(op: String, p: FpParams, latency: Int, family: FpgaFamily): String =
    if (rootOp(op).isDefined) s"Fp${op.capitalize}_${p.name}_dr_L$latency"
    else s"Fp${op.capitalize}_${p.name}_L$latency${family.moduleSuffix}"

  private val builder = scopt.OParser.builder[Opts]
  private val parser = {
    import builder._
    scopt.OParser.sequence(
      programName("collide.fp.report.OperatorGen"),
      opt[String]("op").valueName("add|mul|sqrt|recip|rsqrt").action((v, o) => o.copy(op = v))
        .validate(v => if (ops.contains(v)) success else failure(s"--op '$v': expected one of ${ops.mkString(", ")}")),
      opt[String]("format").valueName("F").action((v, o) => o.copy(format = v)).text("fp16, bf16, fp24, fp32, fp64 or eEmM"),
      opt[Boolean]("subnormals").valueName("true|false").action((v, o) => o.copy(subnormals = v)),
      opt[Int]("latency").valueName("N").action((v, o) => o.copy(latency = Some(v))),
      opt[Double]("mhz").valueName("F").action((v, o) => o.copy(mhz = Some(v)))
        .validate(v => if (v > 0) success else failure(s"--mhz $v: must be above 0")),
      opt[String]("family").valueName("NAME").action((v, o) => o.copy(family = v))
        .text(s"whose DSP tiles and delays place the registers: ${FpgaFamily.all.map(_.name).mkString(", ")}"),
      opt[String]("out").valueName("DIR").action((v, o) => o.copy(out = v)),
      checkConfig(o => if (o.latency.isDefined == o.mhz.isDefined) failure("give exactly one of --latency and --mhz") else success)
    )
  }

  def main(args: Array[String]): Unit = {
    val o = scopt.OParser.parse(parser, args, Opts()).getOrElse(sys.exit(2))
    val fail = (m: String) => { System.err.println(s"OperatorGen: $m"); sys.exit(2) }
    val fam = FpgaFamily.parse(o.family).fold(fail, identity)
    val p = FpParams(FloatFormat.parse(o.format).fold(fail, identity), o.subnormals)
    val delays = if (o.op == "add") FpAdd.delays(p, fam) else FpMul.delays(p, fam)
    val shown = delays.map(d => f"$d%.0f").mkString(" ")
    // A digit-recurrence root has no delay model: at a clock, every stage is registered
    // (one iteration, or one piece of the unpack or the rounder, a stage: RootLatency).
    val lat = rootOp(o.op).map(r => o.latency.getOrElse(RootCoreSelect.cuts(r, p.format.sigBits, RootAlgorithm.DigitRecurrence) + 7)).getOrElse(o.latency.getOrElse {
      val mhz = o.mhz.get
      Pipeline.latencyFor(fam.budget(mhz), delays).fold(
        worst => fail(f"--mhz $mhz%.1f: ${o.op} ${p.name} has a stage of $worst%.0f ps on ${fam.name} (stages, ps: $shown), longer than the ${fam.budget(mhz)}%.0f ps a stage may take"),
        identity)
    })
    if (rootOp(o.op).isEmpty)
      System.err.println(f"${o.op} ${p.name} on ${fam.name}: stages (ps, estimated) $shown; latency $lat, longest run ${Pipeline.longestRun(lat, delays)}%.0f ps")
    val name = moduleName(o.op, p, lat, fam)
    Files.createDirectories(Paths.get(o.out))
    val sv = _root_.circt.stage.ChiselStage.emitSystemVerilog(new TimedOperator(o.op, p, lat, fam),
      firtoolOpts = collide.Generate.firtoolOpts)
    val file = Paths.get(o.out, s"Timed_$name.sv")
    Files.writeString(file, sv)
    println(s"$file Timed_$name $lat")
  }
}
