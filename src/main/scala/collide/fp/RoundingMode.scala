package collide.fp

import chisel3._

/** IEEE-754 rounding-direction attributes, encoded as RISC-V's `rm` field so the hardware
  * input is a 3-bit UInt and tests can sweep all modes through one elaborated design.
  */
sealed abstract class RoundingMode(val code: Int, val name: String) {
  def hw: UInt = code.U(3.W)
  override def toString: String = name
}

object RoundingMode {
  /** Round to nearest, ties to even (IEEE default). */
  case object RNE extends RoundingMode(0, "RNE")
  /** Round toward zero. */
  case object RTZ extends RoundingMode(1, "RTZ")
  /** Round down, toward -infinity. */
  case object RDN extends RoundingMode(2, "RDN")
  /** Round up, toward +infinity. */
  case object RUP extends RoundingMode(3, "RUP")
  /** Round to nearest, ties away from zero. */
  case object RMM extends RoundingMode(4, "RMM")

  val all: Seq[RoundingMode] = Seq(RNE, RTZ, RDN, RUP, RMM)

  def parse(s: String): Either[String, RoundingMode] =
    all.find(_.name.equalsIgnoreCase(s.trim))
      .toRight(s"rounding mode '$s': expected one of ${all.map(_.name).mkString(", ")}")

  def fromCode(c: Int): RoundingMode = all.find(_.code == c).getOrElse(
    throw new IllegalArgumentException(s"rounding mode code $c: expected 0..4"))
}

/** Exception flags, in RISC-V fflags bit order so a 5-bit UInt carries them in hardware. */
object FpFlags {
  val Inexact   = 1 << 0 // NX
  val Underflow = 1 << 1 // UF
  val Overflow  = 1 << 2 // OF
  val DivByZero = 1 << 3 // DZ
  val Invalid   = 1 << 4 // NV
  val width     = 5

  def show(f: Int): String =
    Seq(Invalid -> "NV", DivByZero -> "DZ", Overflow -> "OF", Underflow -> "UF", Inexact -> "NX")
      .collect { case (b, n) if (f & b) != 0 => n }.mkString("|") match {
      case "" => "-"
      case s  => s
    }
}
