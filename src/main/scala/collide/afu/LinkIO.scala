package collide.afu

import chisel3._
import chisel3.util._

/** CCI-style link channels as seen from the AFU (docs/afu-interface.md, "Link channels").
  * Every address is a line address (byte address / 64); data is one 64-byte line, byte b at
  * bits [8b+7 : 8b] (little-endian).
  */
object Link {
  val lineBits  = 512
  val lineBytes = 64
  val addrBits  = 64
  val csrIndexBits = 8
  val csrDataBits  = 64
}

class RdReq(val tagBits: Int) extends Bundle {
  val addr = UInt(Link.addrBits.W)
  val tag  = UInt(tagBits.W)
}
class RdResp(val tagBits: Int) extends Bundle {
  val tag  = UInt(tagBits.W)
  val data = UInt(Link.lineBits.W)
}
class WrReq(val tagBits: Int) extends Bundle {
  val addr = UInt(Link.addrBits.W)
  val tag  = UInt(tagBits.W)
  val data = UInt(Link.lineBits.W)
}
class WrResp(val tagBits: Int) extends Bundle {
  val tag = UInt(tagBits.W)
}
class CsrWrite extends Bundle {
  val index = UInt(Link.csrIndexBits.W)
  val data  = UInt(Link.csrDataBits.W)
}

/** The AFU's side of the link: requests out with back-pressure, responses in without. */
class LinkIO(val tagBits: Int) extends Bundle {
  val rdReq  = Decoupled(new RdReq(tagBits))
  val rdResp = Flipped(Valid(new RdResp(tagBits)))
  val wrReq  = Decoupled(new WrReq(tagBits))
  val wrResp = Flipped(Valid(new WrResp(tagBits)))
  val csr    = Flipped(Valid(new CsrWrite))
}
