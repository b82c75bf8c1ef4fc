package collide.fp

import chisel3._
import chisel3.util._

/** The contract every significand core for sqrt / reciprocal / rsqrt implements (digit
  * recurrence and Newton-Raphson alike), so the operator modules pick a core by algorithm.
  *
  * Input: sig (sigBits wide, top bit set) is m = sig / 2^(sigBits-1) in [1,2); x = 2m when
  * expOdd and the op is Sqrt or Rsqrt, else x = m. Let v = sqrt(x), 1/x or 1/sqrt(x).
  * Output: expDec says v < 1 (then the core returns 2v), so the returned value w = v or 2v
  * lies in [1,2); sig holds w as sigBits bits, then a round bit, then a sticky bit (RoundIn's
  * layout). A correctly rounding core makes round/sticky exact; an approximate core returns
  * its approximation in the same layout. The output appears exactly `latency` enabled
  * cycles after the input.
  */
class RootCoreIO(val sigBits: Int) extends Bundle {
  val en  = Input(Bool())
  val in  = Input(Valid(new Bundle { val sig = UInt(sigBits.W); val expOdd = Bool() }))
  val out = Output(Valid(new Bundle { val sig = UInt((sigBits + 2).W); val expDec = Bool() }))
}
