package collide.fp

import chisel3._

/** Picks the significand core for a root-type operator by algorithm: the one place that
  * names both cores and both core models, so the operators and RootModel stay algorithm-blind.
  */
object RootCoreSelect {
  /** Instantiates the core; its io follows RootCoreIO with exactly `latency` cycles. */
  def apply(op: RootOp, sigBits: Int, alg: RootAlgorithm, latency: Int): RootCoreIO = alg match {
    case RootAlgorithm.DigitRecurrence   => Module(new DigitRecurrenceCore(op, sigBits, latency)).io
    case nr: RootAlgorithm.NewtonRaphson => Module(new NewtonRaphsonCore(op, sigBits, nr, latency)).io
  }

  /** Golden model of the Newton-Raphson core (branch fp-nr). */
  def nrModel(op: RootOp, nr: RootAlgorithm.NewtonRaphson, sigBits: Int, sig: BigInt, expOdd: Boolean): (BigInt, Boolean) =
    collide.fp.model.NewtonRaphsonModel.core(op, nr, sigBits, sig, expOdd)

  /** Largest latency the operator accepts for `alg`: the core's own bound plus the operator's
    * seven registers (RootLatency; DigitRecurrence has no bound). */
  def maxOperatorLatency(op: RootOp, alg: RootAlgorithm): Int = alg match {
    case RootAlgorithm.DigitRecurrence   => Int.MaxValue
    case nr: RootAlgorithm.NewtonRaphson => NewtonRaphsonCore.maxLatency(op, nr) + 7
  }

  /** Registers the core can place where each cuts a path: one an iteration of the digit
    * recurrence and one after its initial state, one a cut of the Newton-Raphson core (its
    * natural latency). */
  def cuts(op: RootOp, sigBits: Int, alg: RootAlgorithm): Int = alg match {
    case RootAlgorithm.DigitRecurrence   => sigBits + 1
    case nr: RootAlgorithm.NewtonRaphson => NewtonRaphsonCore.naturalLatency(op, nr)
  }
}
