package collide.afu

/** Block-RAM estimate for Stratix V, the paper's FPGA (5SGXEA7: 2,560 M20K blocks of 20 Kbit).
  * An M20K's depth x width modes (Intel, "M20K memory block" in the Quartus help): true
  * dual-port 16K x 1, 8K x 2, 4K x 5, 2K x 10, 1K x 20 (two ports, each read or write: what a
  * copy with two read ports and a write while loading needs); simple dual-port (one write, one
  * read) adds 512 x 40. A RAM takes the mode that needs the fewest blocks. An estimate: the
  * fitter may also use MLABs or pack two small RAMs in one block. */
object M20k {
  val deviceBlocks: Int = 2560
  private val trueDual = Seq(16384 -> 1, 8192 -> 2, 4096 -> 5, 2048 -> 10, 1024 -> 20)
  private val simpleDual = trueDual :+ (512 -> 40)
  private def up(a: Long, b: Long): Long = (a + b - 1) / b

  /** Blocks for one RAM of `depth` words of `width` bits. */
  def blocks(depth: Long, width: Int, twoPorts: Boolean): Long =
    (if (twoPorts) trueDual else simpleDual).map { case (d, w) => up(width, w) * up(depth, d) }.min
}
