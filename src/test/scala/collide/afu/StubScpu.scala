package collide.afu

import chisel3._
import chisel3.util._
import collide.scpu.{ScpuIn, ScpuOut}

/** TEST ONLY: a stand-in compute unit with the SCPU's ports and a made-up, cheap function
  * (StubScpu.model), so the PUC's plumbing (ordering, accounting, errors, back-pressure) can
  * be tested on many worlds quickly and without the floating-point datapath. `latency`
  * stages, each a one-entry pipe queue, so it stalls like a pipeline. */
class StubScpu(w: Int, tagBits: Int, latency: Int) extends Module {
  override def desiredName = s"StubScpu_w${w}_L$latency"
  val io = IO(new Bundle {
    val in  = Flipped(Decoupled(new ScpuIn(w, tagBits)))
    val out = Decoupled(new ScpuOut(w, tagBits))
  })
  val i = io.in.bits
  val o = Wire(new ScpuOut(w, tagBits))
  val hit = (i.x1(3, 0) ^ i.y2(3, 0)) < 5.U
  o.hit := hit
  o.kind := Mux(hit, Mux(i.z1(0), 2.U, 1.U), 0.U)
  o.px := Mux(hit, i.x1, 0.U); o.py := Mux(hit, i.y1, 0.U); o.pz := Mux(hit, i.z1, 0.U)
  o.nx := Mux(hit, i.x2, 0.U); o.ny := Mux(hit, i.y2, 0.U); o.nz := Mux(hit, i.z2, 0.U)
  o.depth := Mux(hit, i.r1 ^ i.r2, 0.U)
  // d and w only for a Contact (kind 1), as the real SCPU
  o.d  := Mux(hit && !i.z1(0), i.x1 ^ i.z2, 0.U)
  o.nw := Mux(hit && !i.z1(0), i.y1 ^ i.r2, 0.U)
  o.nonFinite := i.r1(w - 2, w - 9).andR
  // overflow in one pair of eight: a flagged miss is a compact record too, and real
  // arithmetic flags are rare, so the stub should not make them the bulk of the writes
  o.flags := Mux(i.r2(3, 1).andR, collide.fp.FpFlags.Overflow.U, 0.U) | Mux(i.r2(2), collide.fp.FpFlags.Inexact.U, 0.U)
  o.tag := i.tag
  val stages = (0 until latency).foldLeft {
    val d = Wire(Decoupled(new ScpuOut(w, tagBits))); d.valid := io.in.valid; d.bits := o; io.in.ready := d.ready; d
  }((acc, _) => Queue(acc, 1, pipe = true))
  io.out <> stages
}

object StubScpu {
  /** The stub's function on link-format words (x1..r2), as the record the AFU should write. */
  def model(lay: BufferLayout, s1: Seq[BigInt], s2: Seq[BigInt], pair: Int): AfuRecord = {
    val w = lay.linkWidth
    val Seq(x1, y1, z1, r1) = s1; val Seq(x2, y2, z2, r2) = s2
    val hit = ((x1 & 15) ^ (y2 & 15)) < 5
    val kind = if (!hit) 0 else if (z1.testBit(0)) 2 else 1
    val expMask = BigInt(0xff) << (w - 9)
    val nonFinite = (r1 & expMask) == expMask
    val arith = r2.testBit(1) && r2.testBit(2) && r2.testBit(3)
    val z = BigInt(0)
    val flags = (if (hit) 1 else 0) | (kind << 1) | (if (nonFinite) 8 else 0) | (if (arith) 16 else 0)
    val full = if (hit) Seq(x1, y1, z1, x2, y2, z2, r1 ^ r2) else Seq.fill(7)(z)
    val derived = if (kind == 1) Seq(x1 ^ z2, y1 ^ r2) else Seq(z, z)
    AfuRecord(if (lay.records.fields == RecordLayout.fullFields) full else derived, pair, flags)
  }
}

/** TEST ONLY: the PUC with N stub units, link ports as the AFU's. */
class PucHarness(p: PucParams, stubLatency: Int) extends Module {
  val io = IO(new AfuIO(p.tagBits))
  val dbg = IO(Output(Vec(8, UInt(32.W))))
  val puc = Module(new Puc(p))
  dbg := puc.io.dbg
  io.attach(puc)
  for (s <- 0 until p.scpus) {
    val u = Module(new StubScpu(p.linkWidth, p.scpuTagBits, stubLatency))
    u.io.in <> puc.io.scpuIn(s)
    puc.io.scpuOut(s) <> u.io.out
  }
}
