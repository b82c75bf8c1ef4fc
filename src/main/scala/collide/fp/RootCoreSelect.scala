package collide.fp

import chisel3._

/** Picks the significand core for a root-type operator by algorithm. The one place that
  * names the Newton-Raphson core and model (branch fp-nr), so the operators and their
  * golden models do not change when it arrives.
  */
object RootCoreSelect {
  /** Instantiates the core; its io follows RootCoreIO with exactly `latency` cycles. */
  def apply(op: RootOp, sigBits: Int, alg: RootAlgorithm, latency: Int): RootCoreIO = alg match {
    case RootAlgorithm.DigitRecurrence => Module(new DigitRecurrenceCore(op, sigBits, latency)).io
    case nr: RootAlgorithm.NewtonRaphson =>
      throw new NotImplementedError(s"${nr.name}: NewtonRaphsonCore is not merged into this branch yet (fp-nr)")
  }

  /** Golden model of the Newton-Raphson core. */
  def nrModel(op: RootOp, nr: RootAlgorithm.NewtonRaphson, sigBits: Int, sig: BigInt, expOdd: Boolean): (BigInt, Boolean) =
    throw new NotImplementedError(s"${nr.name}: NewtonRaphsonModel is not merged into this branch yet (fp-nr)")
}
