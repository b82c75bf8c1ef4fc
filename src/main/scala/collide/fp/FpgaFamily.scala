package collide.fp

/** An FPGA family as the operators see it when they place their pipeline registers: the width
  * of its DSP multiplier tile and a small delay model of its cells, used only to estimate how
  * long each stage of a datapath is (so `latency` registers go where they cut the longest
  * paths, and the smallest latency for a clock can be derived). The estimates are a model, not
  * a timing analysis: bench/area/afu_timing.py and bench/area/pnr_ecp5.py measure the result.
  *
  * Cell delays (ps) for the Intel families are those Yosys ships for its `sta` (the specify
  * blocks of techlibs/intel_alm/common/{alm_sim,dff_sim,dsp_sim}.v: a LUT's slowest input, an
  * arithmetic cell's entry and exit, the carry per bit, a flip-flop's clock-to-output, the
  * 27x27 multiplier). ECP5 has no cell-delay proxy here; its figures are post-route averages
  * (a LUT4 with the route into it, about 1 ns, and the MULT18X18D), so they include routing.
  *
  * @param lutPs       one LUT level (slowest input), ps
  * @param arithInPs   an adder's first arithmetic cell, input to carry out, ps
  * @param carryPs     the carry chain, per bit, ps
  * @param arithOutPs  the last arithmetic cell, carry in to sum out, ps
  * @param clkToQPs    a flip-flop's clock to output, ps
  * @param dspPs       one DSP multiplier tile, input to output (unregistered), ps
  * @param dspTile     the widest unsigned operand one DSP tile multiplies (27 for the 27x27
  *                    mode of Cyclone V, Arria V, Stratix V and Arria 10; 18 for ECP5)
  * @param lutInputs   inputs of a LUT (6 for an ALM's fracturable LUT, 4 for ECP5)
  */
final case class FpgaFamily(
    name: String,
    lutPs: Int,
    arithInPs: Int,
    carryPs: Int,
    arithOutPs: Int,
    clkToQPs: Int,
    dspPs: Int,
    dspTile: Int,
    lutInputs: Int
) {
  require(name.nonEmpty && name.forall(_.isLetterOrDigit), s"FPGA family name '$name': letters and digits only")
  require(Seq(lutPs, arithInPs, carryPs, arithOutPs, clkToQPs, dspPs).forall(_ > 0), s"FPGA family $name: every delay must be > 0")
  require(dspTile >= 9 && lutInputs >= 4, s"FPGA family $name: a DSP tile of at least 9 bits and LUTs of at least 4 inputs")

  private def log(base: Int, n: Int): Int = {
    var levels = 0; var reach = 1
    while (reach < n) { reach *= base; levels += 1 }
    levels
  }
  /** Bits a LUT selects among, as a mux level: 4:1 in a 6-input LUT, 2:1 in a 4-input one. */
  private val muxBits = lutInputs - 4 + 1

  /** `n` levels of LUTs. */
  def luts(n: Int): Double = n.toDouble * lutPs
  /** An `n`-bit adder or comparator on the carry chain, with the LUT level that usually feeds it
    * (a mux, an inversion) counted: the proxy's paths into a chain start with one. */
  def adder(n: Int): Double = lutPs + arithInPs + n.toDouble * carryPs + arithOutPs
  /** A barrel shifter of `width` bits by a `distBits`-bit amount: a mux level per few bits. */
  def shifter(distBits: Int): Double = luts((distBits + muxBits - 1) / muxBits)
  /** OR (or AND) of `n` bits: a LUT tree. */
  def reduce(n: Int): Double = luts(math.max(1, log(lutInputs, n)))
  /** A leading-zero count of `n` bits: a priority tree a LUT's inputs wide, plus the level that
    * forms the count. */
  def lzc(n: Int): Double = luts(math.max(1, log(lutInputs, n)) + 1)
  /** One DSP tile. */
  def dsp: Double = dspPs.toDouble
  /** The time a stage may take at `mhz`: the period less the launching register's clock-to-output. */
  def budget(mhz: Double): Double = 1e6 / mhz - clkToQPs

  /** What module names carry for operators placed for this family: nothing for the default,
    * so two placements never share a name and the default's names stay short. */
  def moduleSuffix: String = if (this == FpgaFamily.default) "" else s"_$name"
}

object FpgaFamily {
  // Yosys 0.23 techlibs/intel_alm/common: MISTRAL_ALUT6 A=>Q, MISTRAL_ALUT_ARITH A=>CO, CI=>CO,
  // CI=>SO, MISTRAL_FF clk=>Q, MISTRAL_MUL27X27 B=>Y.
  val cycloneV: FpgaFamily = FpgaFamily("cyclonev", lutPs = 605, arithInPs = 1082, carryPs = 36, arithOutPs = 368,
    clkToQPs = 731, dspPs = 3928, dspTile = 27, lutInputs = 6)
  val arriaV: FpgaFamily = FpgaFamily("arriav", lutPs = 387, arithInPs = 629, carryPs = 10, arithOutPs = 249,
    clkToQPs = 470, dspPs = 2053, dspTile = 27, lutInputs = 6)
  // Lattice ECP5, speed grade 6, as nextpnr-ecp5 times it after routing (bench/results/pnr):
  // a LUT4 and its input route about 1 ns, a carry about 0.1 ns a bit past a 1.3 ns entry, the
  // MULT18X18D's combinational path about 4.5 ns.
  val ecp5: FpgaFamily = FpgaFamily("ecp5", lutPs = 1000, arithInPs = 1300, carryPs = 100, arithOutPs = 600,
    clkToQPs = 500, dspPs = 4500, dspTile = 18, lutInputs = 4)

  val all: Seq[FpgaFamily] = Seq(cycloneV, arriaV, ecp5)
  /** What the operators are built for unless told otherwise: the slower of the two Intel
    * families the timing proxy models, so a design placed for it meets the clock on both. */
  val default: FpgaFamily = cycloneV

  def parse(s: String): Either[String, FpgaFamily] =
    all.find(_.name.equalsIgnoreCase(s.trim))
      .toRight(s"FPGA family '$s': expected one of ${all.map(_.name).mkString(", ")}")
}
