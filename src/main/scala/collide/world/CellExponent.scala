package collide.world

import chisel3._
import chisel3.util._
import collide.fp.FpParams

/** Chooses the broad phase's cell exponent k while the sphere table streams in, one sphere a
  * cycle, with no pass at the end: it keeps the largeMax+1 largest needs in a sorted register
  * list (an insertion a cycle), so the (largeMax+1)-th largest need, the smallest kept, is
  * always at hand; and the largest coordinate exponent. k = max(that need, top - kCoordOffset,
  * kFloor), as BroadPhaseModel.chooseK. Excluded spheres (nonFinite) are not counted.
  */
class CellExponentIO(p: FpParams) extends Bundle {
  val kWidth = SphereKeys.kWidth(p)
  /** Starts a new world: forget every sphere. */
  val clear = Input(Bool())
  val in = Input(new Bundle {
    val valid = Bool()
    val need = SInt(kWidth.W)
    val needNone = Bool()
    val top = SInt(kWidth.W)
    val topNone = Bool()
    val nonFinite = Bool()
  })
  /** k for the spheres seen so far (valid the cycle after the last one). */
  val k = Output(SInt(kWidth.W))
}

class CellExponent(p: FpParams, bp: BroadPhaseParams) extends Module {
  override def desiredName = s"CellExponent_${p.name}_L${bp.largeMax}_c${bp.cellBits}"
  val io = IO(new CellExponentIO(p))
  private val w = io.kWidth
  private val minK = (-(BigInt(1) << (w - 1))).S(w.W) // stands for "fits any cell" (r <= 0)
  private val slots = bp.largeMax + 1

  // Sorted, largest first; `used` counts filled slots (saturating at `slots`).
  private val kept = RegInit(VecInit(Seq.fill(slots)(minK)))
  private val used = RegInit(0.U(log2Ceil(slots + 1).W))
  private val topMax = RegInit(minK)
  private val anyTop = RegInit(false.B)

  private val take = io.in.valid && !io.in.nonFinite
  private val need = Mux(io.in.needNone, minK, io.in.need)
  // Insertion: slot i takes the new need if it beats kept(i) but not kept(i-1), takes
  // kept(i-1) if the new one beat that, else stays; the last slot's old value drops out.
  private val beats = kept.map(need > _)
  private val inserted = VecInit((0 until slots).map { i =>
    if (i == 0) Mux(beats(0), need, kept(0))
    else Mux(beats(i - 1), kept(i - 1), Mux(beats(i), need, kept(i)))
  })
  // A need that beats no slot still fills the first unused one (all slots are minK there,
  // and a minK need equals them: nothing changes, which is right).
  when(io.clear) {
    kept.foreach(_ := minK); used := 0.U; topMax := minK; anyTop := false.B
  }.elsewhen(take) {
    kept := inserted
    when(used =/= slots.U) { used := used + 1.U }
    when(!io.in.topNone && (!anyTop || io.in.top > topMax)) { topMax := io.in.top }
    when(!io.in.topNone) { anyTop := true.B }
  }

  // Fewer spheres than slots: all in the grid, sized for the biggest (kept(0)); else the
  // smallest kept need, the (largeMax+1)-th largest.
  private val kSmall = Mux(used === slots.U, kept(slots - 1), kept(0))
  private val kCoord = Mux(anyTop, topMax -& bp.kCoordOffset.S, minK)
  private val kFloor = bp.kFloor(p).S(w.W)
  private def max(a: SInt, b: SInt) = Mux(a > b, a, b)
  io.k := max(max(kSmall, kCoord), kFloor).asTypeOf(SInt(w.W))
}
