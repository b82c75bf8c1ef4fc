package collide.afu

import chisel3._
import chisel3.util._

/** One sphere in the link format. */
class Sphere(w: Int) extends Bundle {
  val x = UInt(w.W); val y = UInt(w.W); val z = UInt(w.W); val r = UInt(w.W)
  /** x, y, z, r in order (the broad phase's sphere ports). */
  def fields: Vec[UInt] = VecInit(x, y, z, r)
}
object Sphere {
  /** The sphere of `w`-bit fields at bit `b` of a RAM word or link line (x lowest). */
  def at(word: UInt, b: Int, w: Int): Sphere = {
    val sp = Wire(new Sphere(w))
    sp.x := word(b + w - 1, b); sp.y := word(b + 2 * w - 1, b + w)
    sp.z := word(b + 3 * w - 1, b + 2 * w); sp.r := word(b + 4 * w - 1, b + 3 * w)
    sp
  }
}

/** The on-chip sphere table (the paper's VWIRB): written a whole host line at a time while
  * loading, read two spheres a cycle per SCPU while computing, one cycle after the address.
  * Replicated: one copy per SCPU, each a line-wide RAM (spheresPerLine spheres a word) with
  * one write and two read ports; the sphere within the line is selected after the read.
  * Banked: one copy in `banks` RAMs a sphere wide (sphere s in bank s mod banks, row
  * s / banks), each with one write and two read ports; a line write meets spheresPerLine
  * banks once each. The reader names the port of every read (`rport`: 0 for the first sphere
  * of a bank in the cycle, 1 for the second; reads of one sphere share its port) and never
  * sends a bank a third sphere (PairDispatcher cuts its groups so); each read's data is routed
  * back from its bank and port.
  * World mode adds line-wide copies for the broad phase's lanes, two lanes a copy (a block RAM's
  * two read ports; one port when a lane is left over), always enabled.
  * With a run queue (`tables` = 2) every RAM is two RAMs, one a table: the queued run's table is
  * written into one (its write port) while this run's is read from the other (its two read
  * ports), so no block RAM ever needs a third port.
  */
class SphereRam(p: PucParams) extends Module {
  override def desiredName =
    s"SphereRam_s${p.maxSpheres}_c${p.ramCopies}" + (if (p.banks > 1) s"_b${p.banks}" else "") +
      (if (p.tables > 1) s"_t${p.tables}" else "") + p.name
  private val spl   = p.layout.spheresPerLine
  private val depth = p.maxSpheres / spl
  private val idxBits = log2Ceil(p.maxSpheres)
  val io = IO(new Bundle {
    val write = Flipped(Valid(new SphereLineWrite(math.max(p.sphereLineBits, 1))))
    /** With two tables: the table written, and the table read (never the same while both are
      * in use: the PUC loads a queued run's table only into the table not read). */
    val wtable = Input(UInt(1.W))
    val rtable = Input(UInt(1.W))
    /** The table the broad phase's copies read: rtable, except while a queued world's broad
      * phase starts ahead on the table just loaded as the SCPUs finish the current run's. */
    val worldTable = Input(UInt(1.W))
    /** Per SCPU, two reads (sphere i, sphere j); data the next cycle. */
    val raddr = Input(Vec(p.scpus, Vec(2, UInt(idxBits.W))))
    val ren   = Input(Vec(p.scpus, Bool()))
    val rdata = Output(Vec(p.scpus, Vec(2, new Sphere(p.linkWidth))))
    /** Banked: each read's port at its bank (at most two spheres a bank a cycle). */
    val rport = if (p.banked) Some(Input(Vec(p.scpus, Vec(2, UInt(1.W))))) else None
    /** World mode: each broad-phase lane's read, data the next cycle. */
    val world = p.world.map(w => Vec(w.bp.lanes, new Bundle {
      val addr = Input(UInt(idxBits.W))
      val data = Output(new Sphere(p.linkWidth))
    }))
  })
  private def sphereAt(word: UInt, b: Int): Sphere = Sphere.at(word, b, p.linkWidth)
  private def unpack(line: UInt, k: UInt): Sphere = VecInit.tabulate(spl)(s => sphereAt(line, s * 4 * p.linkWidth))(k)
  /** One RAM of `rows` words a table, as `p.tables` memories. */
  private class Tables(rows: Int, width: Int) {
    private val mems = Seq.fill(p.tables)(SyncReadMem(rows, UInt(width.W)))
    private def at(row: UInt): UInt = if (rows == 1) 0.U else row(log2Ceil(rows) - 1, 0)
    private def mine(sel: UInt, t: Int): Bool = if (p.tables == 1) true.B else sel === t.U
    def write(row: UInt, data: UInt, en: Bool): Unit =
      for ((m, t) <- mems.zipWithIndex) when(en && mine(io.wtable, t)) { m.write(at(row), data) }
    def read(row: UInt, en: Bool, table: UInt = io.rtable): UInt = {
      val words = mems.zipWithIndex.map { case (m, t) => m.read(at(row), en && mine(table, t)) }
      if (p.tables == 1) words.head else Mux(RegEnable(table, en) === 1.U, words(1), words(0))
    }
  }
  p.ramPorts match {
    case SphereRamPorts.Replicated =>
      for (c <- 0 until p.scpus) {
        val mem = new Tables(depth, Link.lineBits)
        mem.write(io.write.bits.line, io.write.bits.data, io.write.valid)
        for (port <- 0 until 2) {
          val a = io.raddr(c)(port)
          val word = mem.read(a(idxBits - 1, log2Ceil(spl)), io.ren(c))
          val sel = RegEnable(a(log2Ceil(spl) - 1, 0), io.ren(c))
          io.rdata(c)(port) := unpack(word, sel)
        }
      }
    case _: SphereRamPorts.Banked =>
      val nb = p.banks
      val bankBits = log2Ceil(nb)
      val rows = p.maxSpheres / nb
      val sphereBits = 4 * p.linkWidth
      val groupBits = log2Ceil(nb / spl) // lines that fill every bank once
      val banks = Seq.fill(nb)(new Tables(rows, sphereBits))
      val line = io.write.bits.line
      for ((mem, b) <- banks.zipWithIndex) {
        // Line l holds spheres l*spl + k: bank b takes sphere k = b mod spl of the lines with
        // l mod (nb / spl) = b / spl, at row l / (nb / spl).
        val k = b % spl
        val hit = if (groupBits == 0) true.B else line(groupBits - 1, 0) === (b / spl).U
        mem.write((line >> groupBits).asUInt, io.write.bits.data(sphereBits * (k + 1) - 1, sphereBits * k), io.write.valid && hit)
      }
      val reads = for (c <- 0 until p.scpus; port <- 0 until 2) yield (c, port)
      def bankOf(a: UInt): UInt = SphereRam.bankOf(p, a)
      def rowOf(a: UInt): UInt = if (rows == 1) 0.U else a(idxBits - 1, bankBits)
      val out = for ((mem, b) <- banks.zipWithIndex) yield Seq.tabulate(2) { q =>
        val sel = reads.map { case (c, port) =>
          io.ren(c) && bankOf(io.raddr(c)(port)) === b.U && io.rport.get(c)(port) === q.U
        }
        val row = Mux1H(sel, reads.map { case (c, port) => rowOf(io.raddr(c)(port)) })
        // Reads share a port only when they read one sphere (Mux1H then ORs equal rows).
        for ((s, (c, port)) <- sel.zip(reads))
          assert(!s || rowOf(io.raddr(c)(port)) === row, s"SphereRam: two rows on bank $b port $q in one cycle")
        mem.read(row, sel.reduce(_ || _))
      }
      val words = VecInit(out.flatten) // bank b port q at 2b + q
      for ((c, port) <- reads) {
        val at = RegEnable(Cat(bankOf(io.raddr(c)(port)), io.rport.get(c)(port)), io.ren(c))
        io.rdata(c)(port) := sphereAt(words(at), 0)
      }
  }
  for (lanes <- io.world; pair <- lanes.grouped(2)) {
    val mem = new Tables(depth, Link.lineBits)
    mem.write(io.write.bits.line, io.write.bits.data, io.write.valid)
    for (w <- pair) {
      val word = mem.read(w.addr(idxBits - 1, log2Ceil(spl)), true.B, io.worldTable)
      w.data := unpack(word, RegNext(w.addr(log2Ceil(spl) - 1, 0)))
    }
  }
}

object SphereRam {
  /** The bank of sphere `a` in a banked table: a mod banks (PairDispatcher counts its reads
    * per bank with the same map). */
  def bankOf(p: PucParams, a: UInt): UInt = if (p.banks == 1) 0.U else a(log2Ceil(p.banks) - 1, 0)
}
