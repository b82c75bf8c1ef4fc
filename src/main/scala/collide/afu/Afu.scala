package collide.afu

import chisel3._
import collide.scpu.{Scpu, ScpuImpl, ScpuModelUnit}

/** The AFU's ports: the link channels (io_rdReq_valid, io_rdReq_bits_addr, ...) plus the
  * simulation-side idle/skip pair and a busy flag (docs/afu-interface.md, "Idle and skipping").
  * On an FPGA `skipCycles` is tied to 0 and `idle`/`busy` are left open. */
class AfuIO(tagBits: Int) extends LinkIO(tagBits) {
  val busy       = Output(Bool())
  val idle       = Output(Bool())
  val skipCycles = Input(UInt(32.W))

  /** Wires these ports to a PUC (the AFU top and the PUC test harness share this). */
  def attach(puc: Puc): Unit = {
    rdReq <> puc.io.link.rdReq
    puc.io.link.rdResp := rdResp
    wrReq <> puc.io.link.wrReq
    puc.io.link.wrResp := wrResp
    puc.io.link.csr := csr
    busy := puc.io.busy
    idle := puc.io.idle
    puc.io.skipCycles := skipCycles
  }
}

/** The accelerator: the PUC and N SCPUs behind the link of docs/afu-interface.md. */
class Afu(val cfg: AfuConfig) extends Module {
  override def desiredName = s"Afu_${cfg.id}"
  val io = IO(new AfuIO(cfg.tagBits))
  val puc = Module(new Puc(cfg.puc))
  io.attach(puc)
  if (cfg.scpuImpl == ScpuImpl.Rtl) {
    val units = Seq.fill(cfg.scpus)(Module(new Scpu(cfg.scpu)))
    for ((u, s) <- units.zipWithIndex) {
      u.io.in <> puc.io.scpuIn(s)
      puc.io.scpuOut(s) <> u.io.out
    }
  } else {  // simulation only: the C++ model behind the SCPU's pipeline (ScpuModelUnit)
    val models = Seq.fill(cfg.scpus)(Module(new ScpuModelUnit(cfg.scpu, ScpuModelUnit.moduleName(cfg.id))))
    for ((u, s) <- models.zipWithIndex) {
      u.io.clock := clock
      u.io.reset := reset
      u.io.in <> puc.io.scpuIn(s)
      puc.io.scpuOut(s) <> u.io.out
    }
  }
}
