package collide.world

import chisel3._
import chisel3.util._
import collide.fp.FpParams

/** Chooses the broad phase's cell level while the sphere table streams in, `ports`
  * spheres a cycle, with no pass at the end: it keeps the largeMax+1 largest needs in a sorted
  * register list (`ports` insertions a cycle, one after the other in logic), so the (largeMax+1)-th largest need, the smallest kept, is
  * always at hand; and the largest coordinate exponent. The level is max(that need,
  * 2 top - levelCoordOffset, levelFloor), as BroadPhaseModel.chooseLevel. Excluded spheres
  * (nonFinite) are not counted.
  */
/** One sphere's need and top for CellExponent. */
class CellExponentIn(kWidth: Int) extends Bundle {
  val valid = Bool()
  val need = SInt(kWidth.W)
  val needNone = Bool()
  val top = SInt(kWidth.W)
  val topNone = Bool()
  val nonFinite = Bool()
}

class CellExponentIO(p: FpParams, ports: Int, slots: Int) extends Bundle {
  val kWidth = SphereKeys.kWidth(p)
  /** Starts a new world: forget every sphere. */
  val clear = Input(Bool())
  val in = Input(Vec(ports, new CellExponentIn(kWidth)))
  /** The cell level for the spheres seen so far (valid 1 + CellExponent.levelLatency cycles
    * after the last one). */
  val level = Output(SInt(kWidth.W))
  /** What it keeps, for merging several of these into one (BroadPhase's load pass with lanes):
    * the kept needs, largest first, the first `used` of them filled; the largest top, if any. */
  val kept = Output(Vec(slots, SInt(kWidth.W)))
  val used = Output(UInt(log2Ceil(slots + 1).W))
  val top = Output(SInt(kWidth.W))
  val anyTop = Output(Bool())
}

class CellExponent(p: FpParams, bp: BroadPhaseParams, ports: Int = 1) extends Module {
  require(ports >= 1 && ports <= 2, s"ports must be 1 or 2, got $ports")
  override def desiredName = s"CellExponent_${p.name}_L${bp.largeMax}_c${bp.cellBits}_e${bp.cellSteps}" + (if (ports > 1) s"_p$ports" else "")
  val io = IO(new CellExponentIO(p, ports, bp.largeMax + 1))
  private val w = io.kWidth
  private val minK = (-(BigInt(1) << (w - 1))).S(w.W) // stands for "fits any cell" (r <= 0)
  private val slots = bp.largeMax + 1

  // Sorted, largest first; `used` counts filled slots (saturating at `slots`).
  private val kept = RegInit(VecInit(Seq.fill(slots)(minK)))
  private val used = RegInit(0.U(log2Ceil(slots + 1).W))
  private val topMax = RegInit(minK)
  private val anyTop = RegInit(false.B)

  // Insertion: slot i takes the new need if it beats kept(i) but not kept(i-1), takes
  // kept(i-1) if the new one beat that, else stays; the last slot's old value drops out.
  // A need that beats no slot still fills the first unused one (all slots are minK there,
  // and a minK need equals them: nothing changes, which is right).
  private def insert(list: Vec[SInt], need: SInt): Vec[SInt] = {
    val beats = list.map(need > _)
    VecInit((0 until slots).map { i =>
      if (i == 0) Mux(beats(0), need, list(0))
      else Mux(beats(i - 1), list(i - 1), Mux(beats(i), need, list(i)))
    })
  }
  private def saturate(u: UInt, n: UInt): UInt = Mux(u +& n > slots.U, slots.U, u +& n)
  private def maxS(a: SInt, b: SInt) = Mux(a > b, a, b)
  // Each port's sphere in turn: an excluded one (nonFinite) leaves everything as it was.
  private val after = io.in.foldLeft((kept: Vec[SInt], used: UInt, topMax: SInt, anyTop: Bool)) { case ((ks, u, tm, at), in) =>
    val take = in.valid && !in.nonFinite
    val need = Mux(in.needNone, minK, in.need)
    val hasTop = take && !in.topNone
    val ins = insert(ks, need)
    (VecInit(ins.zip(ks).map { case (a, b) => Mux(take, a, b) }), saturate(u, take.asUInt),
      Mux(hasTop, Mux(at, maxS(tm, in.top), in.top), tm), at || hasTop)
  }
  when(io.clear) {
    kept.foreach(_ := minK); used := 0.U; topMax := minK; anyTop := false.B
  }.otherwise {
    kept := after._1; used := after._2; topMax := after._3; anyTop := after._4
  }

  // Fewer spheres than slots: all in the grid, sized for the biggest (kept(0)); else the
  // smallest kept need, the (largeMax+1)-th largest.
  private val levelSmall = Mux(used === slots.U, kept(slots - 1), kept(0))
  private val levelCoord = Mux(anyTop, (topMax << 1) -& bp.levelCoordOffset.S, minK)
  private val levelFloor = bp.levelFloor(p).S(w.W)
  // Two registered steps (CellExponent.levelLatency), a compare each: the kept need against the
  // floor beside the coordinates' bound, then the greater of the two.
  private val levelA = Reg(SInt(w.W))
  private val levelB = Reg(SInt(levelCoord.getWidth.W))
  private val levelR = Reg(SInt(w.W))
  levelA := maxS(levelSmall, levelFloor)
  levelB := levelCoord
  levelR := maxS(levelA, levelB).asTypeOf(SInt(w.W))
  io.level := levelR
  io.kept := kept; io.used := used; io.top := topMax; io.anyTop := anyTop
}

object CellExponent {
  /** Registers between the kept needs and the level: the level counts a sphere
    * 1 + levelLatency cycles after it came. */
  val levelLatency: Int = 2
}
