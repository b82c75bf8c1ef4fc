package collide.afu

import scala.util.DynamicVariable

/** What an AFU takes of its device, as far as the generator can count it before synthesis:
  * M20K blocks (the PUC's estimate: the sphere table's copies and the broad phase's RAMs, each
  * in its cheapest M20K mode) and DSP tiles (every FP multiplier's product tiles, counted as the
  * design is elaborated; the broad phase's products by constants are not among them). Logic
  * (ALMs) needs synthesis: the area proxy measures it (bench/area/afu_timing.py, into the AFU
  * folder's timing.json), the generator does not guess it.
  *
  * @param m20k       M20K blocks, estimated (the pair buffer and queues not counted)
  * @param dspTiles   DSP tiles of the FP multipliers: an upper bound (a product by a constant
  *                   may take none); None where not elaborated or the SCPUs are a C++ model
  */
final case class AfuResources(m20k: Long, dspTiles: Option[Long]) {
  /** The resources this exceeds on `d`: one sentence each, naming it and the numbers. */
  def overfit(d: Device): Seq[String] =
    Seq(Some(m20k) -> ("M20K blocks", d.m20k.toLong, "by estimate"), dspTiles -> ("DSP blocks", d.dspBlocks.toLong, "one per multiplier tile"))
      .collect { case (Some(used), (what, has, how)) if used > has => s"$what: $used needed ($how), the ${d.name} has $has" }

  def json(d: Device): ujson.Obj = {
    def use(used: Option[Long], has: Long) = used.map(u => ujson.Obj("used" -> u.toDouble, "of" -> has.toDouble,
      "share" -> math.round(1000.0 * u / has) / 1000.0)).getOrElse(ujson.Null)
    ujson.Obj("m20k" -> use(Some(m20k), d.m20k), "dsp" -> use(dspTiles, d.dspBlocks),
      "alms" -> ujson.Null,
      "note" -> ("M20K: the generator's estimate (sphere tables, broad phase); DSP: the FP multipliers' tiles counted at " +
        "elaboration, an upper bound for them, but the broad phase's products by constants are not counted; ALMs: not " +
        "estimated before synthesis. The area proxy (bench/area/afu_timing.py) writes the logic's ALMs and DSP blocks " +
        "against this device into timing.json's area"))
  }
}

object AfuResources {
  /** Counts DSP tiles while a design is elaborated: each FP multiplier reports its tiles. */
  private val census = new DynamicVariable[Option[Array[Long]]](None)

  /** Called by an FP multiplier as it is built. */
  def dspTiles(n: Int): Unit = census.value.foreach(c => c(0) += n)

  /** Runs `elaborate` and returns its result with the DSP tiles its multipliers reported. */
  def counting[T](elaborate: => T): (T, Long) = {
    val c = Array(0L)
    val r = census.withValue(Some(c))(elaborate)
    (r, c(0))
  }

  /** The configuration's resources, with the DSP tiles of its elaboration when there was one. */
  def of(cfg: AfuConfig, dspTiles: Option[Long]): AfuResources =
    AfuResources(cfg.puc.ramM20k + cfg.puc.broadPhaseM20k,
      if (cfg.scpuImpl == collide.scpu.ScpuImpl.Rtl) dspTiles else None)
}
