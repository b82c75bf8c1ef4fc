package collide.world

import chisel3._
import chisel3.util._
import collide.fp.{FpParams, RawFloat}
import collide.util.Tree

/** The least and the greatest x, y and z of the eligible spheres (every field finite) one
  * lane has seen since `clear`, for box buckets (docs/afu.md, "Box buckets";
  * BroadPhaseModel.boxMap). Values are compared as order keys (BoxTracker.key): a float's
  * bits with a negative's inverted and a positive's sign bit set compare as unsigned
  * integers in the float order, so no floating-point compare is needed. */
class BoxTracker(p: FpParams) extends Module {
  override def desiredName = s"BoxTracker_${p.name}"
  val io = IO(new Bundle {
    val clear = Input(Bool())
    val in = Flipped(Valid(Vec(4, UInt(p.width.W)))) // x, y, z, r in the compute format
    /** Some eligible sphere was seen. */
    val any = Output(Bool())
    val lo = Output(Vec(3, UInt(p.width.W))) // order keys
    val hi = Output(Vec(3, UInt(p.width.W)))
  })
  private val any = RegInit(false.B)
  private val lo = Reg(Vec(3, UInt(p.width.W)))
  private val hi = Reg(Vec(3, UInt(p.width.W)))
  private val eligible = io.in.bits.map(b => RawFloat(p, b)).map(r => !r.isNaN && !r.isInf).reduce(_ && _)
  when(io.clear) { any := false.B }
    .elsewhen(io.in.valid && eligible) {
      any := true.B
      for (a <- 0 until 3) {
        val k = BoxTracker.key(io.in.bits(a))
        when(!any || k < lo(a)) { lo(a) := k }
        when(!any || k > hi(a)) { hi(a) := k }
      }
    }
  io.any := any; io.lo := lo; io.hi := hi
}

object BoxTracker {
  /** The order key of a float's bits: unsigned order is the float order (finite values). */
  def key(bits: UInt): UInt = {
    val w = bits.getWidth
    Mux(bits(w - 1), ~bits, bits | (BigInt(1) << (w - 1)).U)
  }
  /** The bits of an order key. */
  def bits(key: UInt): UInt = {
    val w = key.getWidth
    Mux(key(w - 1), key ^ (BigInt(1) << (w - 1)).U, ~key)
  }
  /** The least and greatest of several trackers' keys (those that saw a sphere), in a tree of
    * log2(trackers) compares with a register after each (one compare a cycle: 16 lanes' tree
    * of four was the broad phase's slowest path). The result is right [[mergeLatency]] cycles
    * after the trackers last change. */
  def merge(ts: Seq[BoxTracker]): (Bool, Vec[UInt], Vec[UInt]) = {
    val any = ts.map(_.io.any).reduce(_ || _)
    def pick(f: BoxTracker => UInt, better: (UInt, UInt) => Bool): UInt =
      Tree.reduce(ts.map(t => (t.io.any, f(t)))) { (a, b) =>
        val key = Reg(UInt(a._2.getWidth.W)) // (RegNext would leave the width to inference)
        key := Mux(!a._1 || (b._1 && better(b._2, a._2)), b._2, a._2)
        (RegNext(a._1 || b._1), key)
      }._2
    (any, VecInit.tabulate(3)(a => pick(_.io.lo(a), _ < _)), VecInit.tabulate(3)(a => pick(_.io.hi(a), _ > _)))
  }
  /** Cycles [[merge]] takes to settle: its tree's depth. */
  def mergeLatency(trackers: Int): Int = log2Ceil(trackers)
  /** ceil(log2(x)), 0 for x <= 1: BroadPhase's bucket count for a table. */
  def bitsFor(extent: UInt): UInt = Mux(extent <= 1.U, 0.U, Log2(extent - 1.U) +& 1.U)
}
