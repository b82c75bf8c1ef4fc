package collide.world

import chisel3._
import chisel3.util._
import collide.fp.FpParams

/** Chooses the broad phase's cell level while the sphere table streams in, `ports`
  * spheres a cycle, with no pass at the end: it keeps the largeMax+1 largest needs in a sorted
  * register list (`ports` insertions a cycle, in one step of logic), so the (largeMax+1)-th largest need, the smallest kept, is
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

  // Insertion: a need lands before the first kept need it beats (strictly), so ties keep the
  // older one first; the last slot's old value drops out. A sphere that is not taken, or has no
  // need, inserts minK, which beats no slot: the list stays as it was. Two ports insert at once
  // from compares against the old list only (not one insertion after the other, which put two
  // compare chains in series): hi = the greater need goes first, lo second, so slot i takes
  // L(i-2) once lo beat L(i-2), lo where lo first beats, L(i-1) past hi, hi where hi first
  // beats, else L(i).
  private val takes = io.in.map(in => in.valid && !in.nonFinite)
  private val needs = io.in.zip(takes).map { case (in, t) => Mux(t && !in.needNone, in.need, minK) }
  private def beatsOf(need: SInt): Seq[Bool] = kept.map(need > _)
  private val inserted: Seq[SInt] = if (ports == 1) {
    val beats = beatsOf(needs(0))
    (0 until slots).map { i =>
      if (i == 0) Mux(beats(0), needs(0), kept(0)) else Mux(beats(i - 1), kept(i - 1), Mux(beats(i), needs(0), kept(i)))
    }
  } else {
    val (a, b) = (needs(0), needs(1))
    val aFirst = a >= b
    val (aBeats, bBeats) = (beatsOf(a), beatsOf(b))
    val hiBeats = aBeats.zip(bBeats).map { case (x, y) => Mux(aFirst, x, y) }
    val loBeats = aBeats.zip(bBeats).map { case (x, y) => Mux(aFirst, y, x) }
    val (hi, lo) = (Mux(aFirst, a, b), Mux(aFirst, b, a))
    def at(s: Seq[Bool], i: Int): Bool = if (i < 0) false.B else s(i)
    def old(i: Int): SInt = if (i < 0) minK else kept(i)
    (0 until slots).map { i =>
      Mux(at(loBeats, i - 2), old(i - 2), Mux(at(loBeats, i - 1), lo,
        Mux(at(hiBeats, i - 1), old(i - 1), Mux(hiBeats(i), hi, kept(i)))))
    }
  }
  private val usedNext = Mux(used +& PopCount(takes) > slots.U, slots.U, used +& PopCount(takes))
  // The largest top: every candidate compared with every other at once (the first of equals wins).
  private val tops = topMax +: io.in.zip(takes).map { case (in, t) => Mux(t && !in.topNone, in.top, minK) }
  private val topWins = tops.indices.map { k =>
    tops.indices.filter(_ != k).map(j => if (j < k) tops(k) > tops(j) else tops(k) >= tops(j)).reduce(_ && _)
  }
  private val anyTopNext = anyTop || io.in.zip(takes).map { case (in, t) => t && !in.topNone }.reduce(_ || _)
  when(io.clear) {
    kept.foreach(_ := minK); used := 0.U; topMax := minK; anyTop := false.B
  }.otherwise {
    kept := VecInit(inserted); used := usedNext; topMax := Mux1H(topWins, tops); anyTop := anyTopNext
  }

  // Fewer spheres than slots: all in the grid, sized for the biggest (kept(0)); else the
  // smallest kept need, the (largeMax+1)-th largest.
  private val levelSmall = Mux(used === slots.U, kept(slots - 1), kept(0))
  private val levelCoord = Mux(anyTop, (topMax << 1) -& bp.levelCoordOffset.S, minK)
  private val levelFloor = bp.levelFloor(p).S(w.W)
  private def maxS(a: SInt, b: SInt) = Mux(a > b, a, b)
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
