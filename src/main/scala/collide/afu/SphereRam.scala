package collide.afu

import chisel3._
import chisel3.util._

/** One sphere in the link format. */
class Sphere(w: Int) extends Bundle {
  val x = UInt(w.W); val y = UInt(w.W); val z = UInt(w.W); val r = UInt(w.W)
}

/** The on-chip sphere table (the paper's VWIRB): written a whole host line at a time while
  * loading, read two spheres a cycle per SCPU while computing, one cycle after the address.
  * Replicated: one copy per SCPU, each a line-wide RAM (spheresPerLine spheres a word) with
  * one write and two read ports; the sphere within the line is selected after the read.
  * World mode adds one more copy with one read port, always enabled, for the broad phase.
  */
class SphereRam(p: PucParams) extends Module {
  override def desiredName = s"SphereRam_s${p.maxSpheres}_c${p.ramCopies}${p.name}"
  private val spl   = p.layout.spheresPerLine
  private val depth = p.maxSpheres / spl
  private val idxBits = log2Ceil(p.maxSpheres)
  val io = IO(new Bundle {
    val write = Flipped(Valid(new SphereLineWrite(math.max(p.sphereLineBits, 1))))
    /** Per SCPU, two reads (sphere i, sphere j); data the next cycle. */
    val raddr = Input(Vec(p.scpus, Vec(2, UInt(idxBits.W))))
    val ren   = Input(Vec(p.scpus, Bool()))
    val rdata = Output(Vec(p.scpus, Vec(2, new Sphere(p.linkWidth))))
    /** World mode: the broad phase's read, data the next cycle. */
    val world = p.world.map(_ => new Bundle {
      val addr = Input(UInt(idxBits.W))
      val data = Output(new Sphere(p.linkWidth))
    })
  })
  private def unpack(line: UInt, k: UInt): Sphere = {
    val spheres = VecInit.tabulate(spl) { s =>
      val sp = Wire(new Sphere(p.linkWidth))
      val w = p.linkWidth
      val b = s * 4 * w
      sp.x := line(b + w - 1, b); sp.y := line(b + 2 * w - 1, b + w)
      sp.z := line(b + 3 * w - 1, b + 2 * w); sp.r := line(b + 4 * w - 1, b + 3 * w)
      sp
    }
    spheres(k)
  }
  p.ramPorts match {
    case SphereRamPorts.Replicated =>
      for (c <- 0 until p.scpus) {
        val mem = SyncReadMem(depth, UInt(Link.lineBits.W))
        when(io.write.valid) { mem.write(io.write.bits.line(log2Ceil(depth).max(1) - 1, 0), io.write.bits.data) }
        for (port <- 0 until 2) {
          val a = io.raddr(c)(port)
          val word = if (depth == 1) mem.read(0.U, io.ren(c)) else mem.read(a(idxBits - 1, log2Ceil(spl)), io.ren(c))
          val sel = RegEnable(a(log2Ceil(spl) - 1, 0), io.ren(c))
          io.rdata(c)(port) := unpack(word, sel)
        }
      }
      for (w <- io.world) {
        val mem = SyncReadMem(depth, UInt(Link.lineBits.W))
        when(io.write.valid) { mem.write(io.write.bits.line(log2Ceil(depth).max(1) - 1, 0), io.write.bits.data) }
        val word = if (depth == 1) mem.read(0.U) else mem.read(w.addr(idxBits - 1, log2Ceil(spl)))
        w.data := unpack(word, RegNext(w.addr(log2Ceil(spl) - 1, 0)))
      }
  }
}
