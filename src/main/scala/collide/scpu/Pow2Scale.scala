package collide.scpu

import chisel3._
import chisel3.util._
import collide.fp._

/** x * 2^e for the Robust distance method: the exponent moves, the significand does not, and
  * the format's one rounder (RoundRaw) packs the result, so it is exact unless the result
  * leaves the normal range (then it rounds, overflows or flushes as any operator would).
  * Zeros and infinities keep their sign, NaN becomes the canonical NaN (NV if signaling).
  * Golden twin: ScpuModel.pow2Scale. `latency` registers sit at the output.
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
  private val raw = RawFloat(p, io.in.bits.a)
  private val ri  = Wire(new RoundIn(f, ew))
  ri.isNaN  := raw.isNaN
  ri.isInf  := raw.isInf
  ri.isZero := raw.isZero
  ri.sign   := raw.sign
  ri.sExp   := raw.sExp +& io.in.bits.e
  ri.sig    := Cat(raw.sig, 0.U(2.W))
  ri.flags  := Mux(raw.isSNaN, FpFlags.Invalid.U, 0.U)
  io.out.bits  := Pipeline(RoundRaw(p, ri, io.in.bits.rm), latency, io.en)
  io.out.valid := Pipeline.valid(io.in.valid, latency, io.en)
}
