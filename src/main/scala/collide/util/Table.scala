package collide.util

import chisel3._

/** f of a few bits' value, as a table: a ROM of constants, which synthesis maps to LUTs. For
  * the small compares and sums of control logic (a count against a constant, a position mod
  * N) that synthesis otherwise maps to carry chains: each chain costs its entry and exit
  * delays, and a few in series set a block's clock by the timing proxy (docs/timing.md).
  * Keep `in` narrow: the table has 2^width entries.
  */
object Table {
  def apply(in: UInt, w: Int)(f: Int => Int): UInt = {
    require(in.getWidth <= 12, s"Table: a ${in.getWidth}-bit input is too wide for a table")
    VecInit(Seq.tabulate(1 << in.getWidth)(v => f(v).U(w.W)))(in)
  }
}
