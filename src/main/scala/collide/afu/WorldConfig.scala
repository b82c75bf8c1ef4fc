package collide.afu

import collide.world.BroadPhaseParams

/** World mode in an AFU (MODE bit 1): the on-chip broad phase that finds the pairs, and the
  * settings around it that only world mode has. An AfuConfig without one builds pair lists only.
  *
  * @param broadPhase  the broad phase's parameters (lanes, sort ports, chunks, ...;
  *                    BroadPhaseParams, docs/world-mode-options.md)
  * @param runQueue    a run queue: a start while a run is on queues one more run, and a queued
  *                    world run's table loads into a second on-chip table while the current run
  *                    computes (docs/world-mode-options.md, "The run queue"); costs a second copy
  *                    of every sphere-table RAM
  * @param lineQueue   pair lines of candidates queued between the broad phase and the dispatcher
  *                    (2..4096): deeper lets the lanes run on while a burst of contacts holds the
  *                    SCPUs
  * @param startAhead  with the run queue: a queued world run's broad phase starts as soon as the
  *                    current run's is over and the queued table is in, while the current run's
  *                    last pairs are still computed and written; its candidates wait for its own
  *                    run (docs/world-mode-options.md, "Starting ahead")
  */
final case class WorldConfig(
    broadPhase: BroadPhaseParams = BroadPhaseParams.default,
    runQueue: Boolean = false,
    lineQueue: Int = 2,
    startAhead: Boolean = false) {
  require(lineQueue >= 2 && lineQueue <= 4096, s"the world line queue must be 2..4096 pair lines, got $lineQueue")
  require(!startAhead || runQueue, "starting ahead needs the run queue (it starts the queued world run's broad phase)")

  /** The part of a derived configuration name that world mode adds (docs/afu.md's table of
    * derived names): `_world`, then a code for each setting away from its default. */
  def idSuffix: String = {
    val bp = broadPhase
    val d = BroadPhaseParams.default
    "_world" + (if (bp.lanes > 1) bp.lanes.toString else "") + (if (bp.sortPorts > 1) s"p${bp.sortPorts}" else "") +
      (if (bp.wordLog2 != d.wordLog2) s"w${bp.wordLog2}" else "") +
      (if (bp.bucketsPerSphereLog2 != d.bucketsPerSphereLog2) s"s${bp.bucketsPerSphereLog2}" else "") +
      (if (bp.cellSteps != d.cellSteps) s"e${bp.cellSteps}" else "") +
      (if (bp.chunk != d.chunk) s"k${bp.chunk}" else "") +
      (if (bp.coarseChunks) "x" else "") + (if (bp.claims) "u" else "") + (if (bp.hitQueue > 0) s"h${bp.hitQueue}" else "") +
      (if (bp.boxBuckets) "bx" else "") + (if (bp.drainBehind) "d" else "") + (if (bp.lookAhead != 3) s"a${bp.lookAhead}" else "") +
      (if (bp.scanPairs) "sp" else "") + (if (bp.clearBehind) "cb" else "") + (if (!bp.nearFilter) "wf" else "") +
      (if (lineQueue != 2) s"l$lineQueue" else "") + (if (startAhead) "z" else "")
  }
}
