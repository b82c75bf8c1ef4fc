package collide.afu

import chisel3._
import collide.scpu.Scpu

/** The accelerator: the PUC and N SCPUs behind the link of docs/afu-interface.md. Verilog
  * ports: clock, reset and io_<channel>_<field> (io_rdReq_valid, io_rdReq_bits_addr, ...). */
class Afu(val cfg: AfuConfig) extends Module {
  override def desiredName = s"Afu_${cfg.id}"
  val io = IO(new LinkIO(cfg.tagBits))
  val puc = Module(new Puc(cfg.puc))
  io <> puc.io.link
  val units = Seq.fill(cfg.scpus)(Module(new Scpu(cfg.scpu)))
  for ((u, s) <- units.zipWithIndex) {
    u.io.in <> puc.io.scpuIn(s)
    puc.io.scpuOut(s) <> u.io.out
  }
}
