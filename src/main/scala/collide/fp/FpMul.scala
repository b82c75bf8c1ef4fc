package collide.fp

import chisel3._
import chisel3.util._

/** FpMul's input: a * b rounded by `rm` (RoundingMode.hw). */
class FpMulIn(val w: Int) extends Bundle {
  val a  = UInt(w.W)
  val b  = UInt(w.W)
  val rm = UInt(3.W)
}

/** Floating-point multiplication, fully pipelined, `latency` enabled cycles in to out.
  *
  * RawFloat normalizes subnormal operands, so the significand product always has its top
  * bit at one of the two highest places: one conditional shift normalizes it. The product's
  * exponent spans about twice the format's range (two subnormals multiplied), so RoundIn's
  * exponent is one bit wider than RawFloat's; RoundRaw denormalizes or flushes tiny results.
  *
  * The significand product is built from `family`'s DSP tiles (FpMul.chunks: operands cut
  * into chunks of the tile's width, one product a pair of chunks), summed by a tree of adders.
  * Stages, each ending at a boundary where registers may go: unpack (classify, then normalize
  * subnormal operands), the tiles' products, one stage a level of the adder tree (none when
  * one tile holds the product), normalize, and the rounder's four (locate, jam, increment,
  * pack: the output). Pipeline.balanced places the `latency` registers by their estimated
  * delays (FpMul.delays), output first, so each register up to the stage count cuts the
  * longest path left. The result never depends on the family.
  */
class FpMul(val p: FpParams, val latency: Int, val family: FpgaFamily = FpgaFamily.default) extends Module {
  require(latency >= 0, s"FpMul latency must be >= 0, got $latency")
  private val f = p.format
  val io = IO(new Bundle {
    val en  = Input(Bool())
    val in  = Input(Valid(new FpMulIn(f.width)))
    val out = Output(Valid(new FpOut(f.width)))
  })
  override def desiredName = s"FpMul_${p.name}_L$latency${family.moduleSuffix}"

  private val regs = Pipeline.balanced(latency, FpMul.delays(p, family))
  private def stage[T <: Data](i: Int, x: T): T = Pipeline(x, regs(i), io.en)
  private val ew = FpMul.expWidth(f)
  private val pw = 2 * f.sigBits
  private val chunks = FpMul.chunks(f.sigBits, family.dspTile)
  private val levels = FpMul.treeLevels(f.sigBits, family.dspTile)

  class Carried extends Bundle {
    val isNaN  = Bool()
    val isInf  = Bool()
    val isZero = Bool()
    val sign   = Bool()
    val flags  = UInt(FpFlags.width.W)
    val exp    = SInt(ew.W) // a.sExp + b.sExp: exponent of the product's bit 2*sigBits-2
    val rm     = UInt(3.W)
  }

  // ---- Stages 0 and 1: unpack (classify, then normalize subnormal operands) ----
  class Classified extends Bundle { val a = new RawClass(f); val b = new RawClass(f); val rm = UInt(3.W) }
  private val sc = Wire(new Classified)
  sc.a  := RawFloat.classify(p, io.in.bits.a)
  sc.b  := RawFloat.classify(p, io.in.bits.b)
  sc.rm := io.in.bits.rm
  private val scr = stage(0, sc)
  class Unpacked extends Bundle { val a = new RawFloat(f); val b = new RawFloat(f); val rm = UInt(3.W) }
  private val s0 = Wire(new Unpacked)
  s0.a  := RawFloat.normalize(p, scr.a)
  s0.b  := RawFloat.normalize(p, scr.b)
  s0.rm := scr.rm
  private val s0r = stage(1, s0)

  // ---- Stage 2: specials, the exponent, one product a pair of chunks (a DSP tile each) ----
  private val nParts = chunks.size * chunks.size
  class Parts(n: Int) extends Bundle { val c = new Carried; val parts = Vec(n, UInt(pw.W)) }
  private val s1 = Wire(new Parts(nParts))
  locally {
    val a = s0r.a; val b = s0r.b
    val invalid = (a.isInf && b.isZero) || (a.isZero && b.isInf)
    s1.c.isNaN  := a.isNaN || b.isNaN || invalid
    s1.c.isInf  := a.isInf || b.isInf
    s1.c.isZero := a.isZero || b.isZero
    s1.c.sign   := a.sign ^ b.sign
    s1.c.flags  := Mux(a.isSNaN || b.isSNaN || invalid, FpFlags.Invalid.U, 0.U)
    s1.c.exp    := a.sExp.pad(ew) + b.sExp.pad(ew)
    s1.c.rm     := s0r.rm
    val products = for ((alo, aw) <- chunks; (blo, bw) <- chunks)
      yield (a.sig(alo + aw - 1, alo) * b.sig(blo + bw - 1, blo)) << (alo + blo)
    s1.parts := VecInit(products.map(_.pad(pw)(pw - 1, 0)))
  }
  private val s1r = stage(2, s1)

  // ---- Stages 3 .. 2 + levels: the adder tree, one level a stage ----
  private val summed = (0 until levels).foldLeft(s1r) { (acc, lvl) =>
    val next = Wire(new Parts((acc.parts.length + 1) / 2))
    next.c := acc.c
    next.parts := VecInit(acc.parts.grouped(2).map(g => g.reduce(_ +% _)).toSeq)
    stage(3 + lvl, next)
  }
  private val prod = summed.parts(0)
  private val nb   = 3 + levels // the normalize stage's boundary

  // ---- Normalize (product in [1,4) -> [1,2)) ----
  private val top = prod(pw - 1)
  // sigBits + 1 leading bits then the rest jammed into a sticky bit.
  private val hi  = Mux(top, prod(pw - 1, pw - f.sigBits - 1), prod(pw - 2, pw - f.sigBits - 2))
  private val lo  = Mux(top, prod(pw - f.sigBits - 2, 0).orR, prod(pw - f.sigBits - 3, 0).orR)
  private val sn  = Wire(new RoundIn(f, ew))
  private val c   = summed.c
  sn.isNaN  := c.isNaN
  sn.isInf  := c.isInf && !c.isNaN
  sn.isZero := c.isZero && !c.isNaN && !c.isInf
  sn.sign   := c.sign
  sn.sExp   := c.exp + top.zext
  sn.sig    := Cat(hi, lo)
  sn.flags  := c.flags
  private val snr = stage(nb, sn)
  private val rmr = stage(nb, c.rm)

  // ---- Round ----
  private val sl = stage(nb + 1, RoundRaw.locate(p, snr, rmr))
  private val sj = stage(nb + 2, RoundRaw.jam(p, sl))
  private val si = stage(nb + 3, RoundRaw.increment(p, sj))
  io.out.bits  := stage(nb + 4, RoundRaw.pack(p, si))
  io.out.valid := Pipeline.valid(io.in.valid, latency, io.en)
  // The device census (collide.afu.AfuResources): this multiplier's product tiles.
  collide.afu.AfuResources.dspTiles(FpMul.tiles(f.sigBits, family.dspTile))
}

object FpMul {
  /** One bit wider than RawFloat's exponent: the product's exponent spans twice the range. */
  def expWidth(f: FloatFormat): Int = f.rawExpWidth + 2

  /** The significand cut into chunks of at most `tile` bits: (lowest bit, width), low first. */
  def chunks(sigBits: Int, tile: Int): Seq[(Int, Int)] =
    (0 until sigBits by tile).map(lo => (lo, math.min(tile, sigBits - lo)))

  /** Levels of the adder tree that sums the tiles' products. */
  def treeLevels(sigBits: Int, tile: Int): Int = log2Ceil(tiles(sigBits, tile))

  /** The DSP tiles of one product: every chunk of one operand times every chunk of the other. */
  def tiles(sigBits: Int, tile: Int): Int = chunks(sigBits, tile).size * chunks(sigBits, tile).size

  /** Estimated delay of each stage on `fam` (FpgaFamily's model, ps). */
  def delays(p: FpParams, fam: FpgaFamily): Seq[Double] = {
    val f = p.format; val pw = 2 * f.sigBits
    RawFloat.delays(p, fam) ++ Seq(fam.dsp) ++
      Seq.fill(treeLevels(f.sigBits, fam.dspTile))(fam.adder(pw)) ++
      Seq(fam.reduce(pw - f.sigBits) + fam.luts(1)) ++
      RoundRaw.delays(fam, f, expWidth(f))
  }

  /** The smallest latency whose stages fit `mhz` on `fam`, or Left with the longest stage (ps). */
  def latencyFor(p: FpParams, fam: FpgaFamily, mhz: Double): Either[Double, Int] =
    Pipeline.latencyFor(fam.budget(mhz), delays(p, fam))
}
