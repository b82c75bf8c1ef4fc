package collide.afu

/** An FPGA part an AFU is built for: what it holds, from the maker's tables (the source says
  * which). Only what the generator can check before synthesis is used to refuse a configuration
  * (AfuResources); `alms` is there for the area proxy's figures to be read against.
  *
  * @param name      the part's short name (`--device`)
  * @param part      the part, and the platform that carries it
  * @param alms      adaptive logic modules
  * @param m20k      M20K block RAMs (20 Kbit each)
  * @param dspBlocks variable-precision DSP blocks (each one 27 x 27 product, or two narrower)
  * @param source    where the figures come from
  */
final case class Device(name: String, part: String, alms: Int, m20k: Int, dspBlocks: Int, source: String) {
  require(name.nonEmpty && alms > 0 && m20k > 0 && dspBlocks > 0, s"Device '$name': every resource must be above 0")
}

object Device {
  /** The paper's part: HARP v1's Stratix V GX A7. */
  val stratixVA7: Device = Device("5SGXEA7", "Intel Stratix V GX A7 (HARP v1)", alms = 234720, m20k = 2560, dspBlocks = 256,
    source = "Intel, Stratix V Device Overview (SV51001), Stratix V GX device features: 5SGXA7")
  /** HARP v2's and the Intel PAC's part. */
  val arria10GX1150: Device = Device("10AX115", "Intel Arria 10 GX 1150 (HARP v2, Intel PAC)", alms = 427200, m20k = 2713,
    dspBlocks = 1518, source = "Intel, Intel Arria 10 Device Overview (A10-OVERVIEW), Arria 10 GX resources: GX 1150")

  /** The part of Intel's Stratix 10 accelerator card (the PAC D5005 carries the SX 2800, whose
    * fabric is the GX 2800's): the smallest part on an Intel accelerator platform that holds
    * the `world` preset by the area proxy. */
  val stratix10GX2800: Device = Device("1SG280", "Intel Stratix 10 GX 2800 (the Intel PAC D5005's SX 2800 fabric)",
    alms = 933120, m20k = 11721, dspBlocks = 5760,
    source = "Intel, Intel Stratix 10 GX/SX Device Overview (S10-OVERVIEW), Stratix 10 GX resources: GX 2800")

  val all: Seq[Device] = Seq(stratixVA7, arria10GX1150, stratix10GX2800)
  def byName(s: String): Either[String, Device] =
    all.find(_.name.equalsIgnoreCase(s.trim)).toRight(s"unknown device '$s' (known: ${all.map(_.name).mkString(", ")})")
}
