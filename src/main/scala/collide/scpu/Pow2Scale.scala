package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** x * 2^e for the Robust distance method: the exponent moves, the significand does not, and
  * the format's one rounder (RoundRaw) packs the result, so it is exact unless the result
  * leaves the normal range (then it rounds, overflows or flushes as any operator would).
  * Zeros and infinities keep their sign, NaN becomes the canonical NaN (NV if signaling).
  * Golden twin: ScpuModel.pow2Scale. Five stages (unpack and the exponent's adder, then the
  * rounder's four: RoundRaw.locate, jam, increment, pack); Pipeline.balanced places the `latency`
  * registers among them, the output first.
  */
class Pow2Scale(p: FpParams, val latency: Int) extends Module {
  private val f = p.format
  /** Width of e: any exponent difference between two finite values of the format. */
  val eWidth: Int = f.rawExpWidth + 1
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new Bundle {
      val a  = UInt(f.width.W)
      val e  = SInt(eWidth.W)
      val rm = UInt(3.W)
    }))
    val out = Output(Valid(new FpOut(f.width)))
  })
  override def desiredName = s"Pow2Scale_${p.name}_L$latency"

  private val ew  = eWidth + 1
  private val regs = Pipeline.balanced(latency, Seq(RawFloat.delay(p, FpgaFamily.default) +
    FpgaFamily.default.adder(ew)) ++ RoundRaw.delays(FpgaFamily.default, f, ew))
  private val raw = RawFloat(p, io.in.bits.a)
  private val ri  = Wire(new RoundIn(f, ew))
  ri.isNaN  := raw.isNaN
  ri.isInf  := raw.isInf
  ri.isZero := raw.isZero
  ri.sign   := raw.sign
  ri.sExp   := raw.sExp +& io.in.bits.e
  ri.sig    := Cat(raw.sig, 0.U(2.W))
  ri.flags  := Mux(raw.isSNaN, FpFlags.Invalid.U, 0.U)
  private val riR = Pipeline(ri, regs(0), io.en)
  private val rmR = Pipeline(io.in.bits.rm, regs(0), io.en)
  private val at  = Pipeline(RoundRaw.locate(p, riR, rmR), regs(1), io.en)
  private val mid = Pipeline(RoundRaw.jam(p, at), regs(2), io.en)
  private val inc = Pipeline(RoundRaw.increment(p, mid), regs(3), io.en)
  io.out.bits  := Pipeline(RoundRaw.pack(p, inc), regs(4), io.en)
  io.out.valid := Pipeline.valid(io.in.valid, latency, io.en)
}
