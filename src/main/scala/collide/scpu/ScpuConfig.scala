package collide.scpu

import collide.fp._

/** How the SCPU turns the difference vector (dx, dy, dz) into the distance d and the factor
  * the normal is built from (docs/scpu.md compares them).
  */
sealed trait DistanceMethod { def name: String }
object DistanceMethod {
  /** ODE's own order: d = sqrt(d2); inv = 1/d; n = (dx,dy,dz) * inv. */
  case object SqrtThenRecip extends DistanceMethod { val name = "sqrt-recip" }
  /** inv = rsqrt(d2); d = d2 * inv; n = (dx,dy,dz) * inv. One root operator on the critical
    * path instead of two. d2 = 0 and d2 = inf are guarded (d = d2), since rsqrt(0) = inf and
    * rsqrt(inf) = 0 make d2 * inv a 0 * inf, which IEEE 754 defines as invalid (NaN); docs/scpu.md.
    */
  case object Rsqrt extends DistanceMethod { val name = "rsqrt" }
  /** Scale (dx,dy,dz) by 2^-E, E the exponent of the largest |component|, so the scaled sum of
    * squares lies in [1, 12) and can neither overflow nor underflow; ds = sqrt(scaled d2);
    * d = ds * 2^E (exact unless d itself leaves the format's range); n = (scaled diff) * (1/ds).
    */
  case object Robust extends DistanceMethod { val name = "robust" }

  val all: Seq[DistanceMethod] = Seq(SqrtThenRecip, Rsqrt, Robust)
  def parse(s: String): Either[String, DistanceMethod] =
    all.find(_.name.equalsIgnoreCase(s.trim))
      .toRight(s"distance method '$s': expected one of ${all.map(_.name).mkString(", ")}")
}

/** One SCPU configuration: what it computes (format, rounding, subnormals, algorithms, distance
  * method) and how it is pipelined (per-operator latencies). Every field has a default; the
  * default configuration is the fp32 correctly rounded RNE preset.
  *
  * @param name         the preset name (also in the Verilog module name, see [[id]])
  * @param format       compute format; must fit in IEEE binary64 so the link carries it exactly
  * @param subnormals   false: every operator flushes (DAZ + FTZ), see FpParams
  * @param rounding     the rounding mode, a constant tied to every operator's rm input
  * @param distance     how d and the normal's factor are computed
  * @param sqrtAlg      algorithm of the square root (SqrtThenRecip, Robust)
  * @param recipAlg     algorithm of the reciprocal (SqrtThenRecip, Robust)
  * @param rsqrtAlg     algorithm of the reciprocal square root (Rsqrt)
  * @param cvtLatency   link <-> compute conversions; ignored (no hardware) when the compute
  *                     format is the link format with subnormals kept
  * @param addLatency   FpAdd
  * @param mulLatency   FpMul
  * @param cmpLatency   FpCompare
  * @param sqrtLatency  FpSqrt; None = [[ScpuConfig.defaultRootLatency]] for format and algorithm
  * @param recipLatency FpRecip; None = default as above
  * @param rsqrtLatency FpRsqrt; None = default as above
  * @param scaleLatency the Robust method's power-of-two scaling and unscaling (each)
  * @param tagBits      width of the tag carried through (the AFU's pair index)
  * @param link         the link's number format; None = [[FloatFormat.linkFormat]] of `format`
  *                     (fp16 and bf16 as themselves, else binary32 or binary64)
  * @param family       the FPGA family whose DSP tiles build the multipliers and whose cell
  *                     delays place the adders' and multipliers' registers (FpgaFamily);
  *                     what is computed never depends on it
  */
final case class ScpuConfig(
    name: String = "fp32",
    format: FloatFormat = FloatFormat.fp32,
    subnormals: Boolean = true,
    rounding: RoundingMode = RoundingMode.RNE,
    distance: DistanceMethod = DistanceMethod.SqrtThenRecip,
    sqrtAlg: RootAlgorithm = RootAlgorithm.DigitRecurrence,
    recipAlg: RootAlgorithm = RootAlgorithm.DigitRecurrence,
    rsqrtAlg: RootAlgorithm = RootAlgorithm.DigitRecurrence,
    cvtLatency: Int = 1,
    addLatency: Int = 1,
    mulLatency: Int = 1,
    cmpLatency: Int = 1,
    sqrtLatency: Option[Int] = None,
    recipLatency: Option[Int] = None,
    rsqrtLatency: Option[Int] = None,
    scaleLatency: Int = 1,
    tagBits: Int = 24,
    link: Option[FloatFormat] = None,
    family: FpgaFamily = FpgaFamily.default
) {
  require(name.nonEmpty && name.forall(c => c.isLetterOrDigit || c == '-' || c == '_'),
    s"ScpuConfig name '$name': must be non-empty letters, digits, '-' or '_'")
  require(format.expBits <= FloatFormat.fp64.expBits && format.sigBits <= FloatFormat.fp64.sigBits,
    s"ScpuConfig $name: format ${format.name} does not fit IEEE binary64 (at most 11 exponent and 53 significand bits), so the link could not carry it")
  require(cvtLatency >= 0, s"ScpuConfig $name: cvtLatency must be >= 0, got $cvtLatency")
  require(addLatency >= 0, s"ScpuConfig $name: addLatency must be >= 0, got $addLatency")
  require(mulLatency >= 0, s"ScpuConfig $name: mulLatency must be >= 0, got $mulLatency")
  require(cmpLatency >= 0, s"ScpuConfig $name: cmpLatency must be >= 0, got $cmpLatency")
  require(scaleLatency >= 0, s"ScpuConfig $name: scaleLatency must be >= 0, got $scaleLatency")
  for ((n, l) <- Seq("sqrtLatency" -> sqrtLatency, "recipLatency" -> recipLatency, "rsqrtLatency" -> rsqrtLatency))
    require(l.forall(_ >= 0), s"ScpuConfig $name: $n must be >= 0, got ${l.get}")
  require(tagBits >= 1 && tagBits <= 64, s"ScpuConfig $name: tagBits must be 1..64, got $tagBits")

  val params: FpParams         = FpParams(format, subnormals)
  /** The number format of every field on the link (spheres in, contacts out). */
  val linkFormat: FloatFormat  = link.getOrElse(format.linkFormat)
  require(FloatFormat.linkFormats.contains(linkFormat),
    s"ScpuConfig $name: link format ${linkFormat.name} is not one the host can carry (${FloatFormat.linkFormats.map(_.name).mkString(", ")})")
  require(format.fitsIn(linkFormat),
    s"ScpuConfig $name: link format ${linkFormat.name} does not hold every ${format.name} value")
  val linkParams: FpParams     = FpParams(linkFormat)
  val linkWidth: Int           = linkFormat.width
  val rm: RoundingMode         = rounding

  /** Conversions are hardware only when they change something: a narrower format, or DAZ. */
  val converts: Boolean      = format != linkFormat || !subnormals
  val cvtLat: Int            = if (converts) cvtLatency else 0
  val sqrtLat: Int           = sqrtLatency.getOrElse(ScpuConfig.defaultRootLatency(format, sqrtAlg, RootOp.Sqrt))
  val recipLat: Int          = recipLatency.getOrElse(ScpuConfig.defaultRootLatency(format, recipAlg, RootOp.Recip))
  val rsqrtLat: Int          = rsqrtLatency.getOrElse(ScpuConfig.defaultRootLatency(format, rsqrtAlg, RootOp.Rsqrt))
  for ((op, alg, lat) <- Seq((RootOp.Sqrt, sqrtAlg, sqrtLat), (RootOp.Recip, recipAlg, recipLat), (RootOp.Rsqrt, rsqrtAlg, rsqrtLat))) {
    val max = RootCoreSelect.maxOperatorLatency(op, alg)
    require(lat <= max, s"ScpuConfig $name: ${op.name} latency $lat exceeds ${alg.name}'s maximum $max")
  }

  // Per-stage latencies (cycles), in datapath order; docs/scpu.md draws the schedule.
  /** Link -> compute conversion. */
  val inLatency: Int = cvtLat
  /** dx, dy, dz, r1 + r2, r2 - r1. */
  val diffLatency: Int = addLatency
  /** Sum of squares: squares, then (dx2 + dy2) + dz2. */
  val sumSqLatency: Int = mulLatency + 2 * addLatency
  /** Distance unit, from (dx,dy,dz) to d. */
  val dLatency: Int = distance match {
    case DistanceMethod.SqrtThenRecip => sumSqLatency + sqrtLat
    case DistanceMethod.Rsqrt         => sumSqLatency + rsqrtLat + mulLatency
    case DistanceMethod.Robust        => scaleLatency + sumSqLatency + sqrtLat + scaleLatency
  }
  /** Distance unit, from (dx,dy,dz) to the normal's factors (u, w): n = u * w. */
  val wLatency: Int = distance match {
    case DistanceMethod.SqrtThenRecip => sumSqLatency + sqrtLat + recipLat
    case DistanceMethod.Rsqrt         => sumSqLatency + rsqrtLat
    case DistanceMethod.Robust        => scaleLatency + sumSqLatency + sqrtLat + recipLat
  }
  /** Contact stage, measured from the distance unit's input: k = 0.5 * ((r2 - r1) - d) and
    * n = u * w in parallel, then n * k, then p1 + n * k. */
  val kTime: Int   = dLatency + addLatency + mulLatency
  val nTime: Int   = wLatency + mulLatency
  val posTime: Int = math.max(kTime, nTime) + mulLatency + addLatency
  /** Compute-format datapath (difference to selected outputs; the compare runs beside). */
  val coreLatency: Int = diffLatency + math.max(posTime, dLatency + cmpLatency)
  /** Compute -> link conversion. */
  val outLatency: Int = cvtLat
  /** Cycles from a pair accepted on io.in to its result on io.out. */
  val latency: Int = inLatency + coreLatency + outLatency
  require(latency >= 1, s"ScpuConfig $name: total latency must be >= 1 so the output is registered, got $latency")

  /** Operators instantiated (FpAdd, FpMul, FpCompare, FpConvert, roots), for docs/scpu.md. */
  def operatorCount: Map[String, Int] = {
    val cvt = if (converts) 8 + 9 else 0 // in: 8 sphere fields; out: 7 contact fields and d, w
    val (adds, muls, roots) = distance match {
      case DistanceMethod.SqrtThenRecip => (5 + 2 + 2 + 3, 3 + 3 + 1 + 3, Map("sqrt" -> 1, "recip" -> 1))
      case DistanceMethod.Rsqrt         => (5 + 2 + 2 + 3, 3 + 1 + 3 + 1 + 3, Map("rsqrt" -> 1))
      case DistanceMethod.Robust        => (5 + 2 + 2 + 3, 3 + 3 + 1 + 3, Map("sqrt" -> 1, "recip" -> 1, "pow2scale" -> 4))
    }
    Map("add" -> adds, "mul" -> muls, "compare" -> 1, "convert" -> cvt) ++ roots
  }

  /** True when this configuration is exactly the named preset it claims to be. */
  def isPreset: Boolean = ScpuConfig.presets.get(name).contains(this)

  /** Name for generated modules: the preset name, with a hash of the fields when the
    * configuration has been changed from its preset (so two configurations never share a
    * Verilog module name).
    */
  def id: String = {
    val base = name.replace('-', '_')
    if (isPreset) base else f"${base}_${(toString.hashCode & 0xffffffffL)}%08x"
  }

  /** One line describing every knob, for reports. */
  def describe: String = {
    val roots = distance match {
      case DistanceMethod.Rsqrt => s"rsqrt=${rsqrtAlg.name}/L$rsqrtLat"
      case _                    => s"sqrt=${sqrtAlg.name}/L$sqrtLat recip=${recipAlg.name}/L$recipLat"
    }
    val scale = if (distance == DistanceMethod.Robust) s" scale=L$scaleLatency" else ""
    s"$name: ${format.name}${if (subnormals) "" else " ftz"}${link.fold("")(l => s" link=${l.name}")} $rounding ${distance.name} $roots " +
      s"cvt=L$cvtLat add=L$addLatency mul=L$mulLatency cmp=L$cmpLatency$scale${if (family == FpgaFamily.default) "" else s" family=${family.name}"}, latency $latency"
  }

  /** This configuration with every operator's latency the smallest that cuts its estimated
    * stages to `mhz` on its family (FpAdd.latencyFor, FpMul.latencyFor), the roots' every stage
    * registered (one digit-recurrence iteration or Newton-Raphson cut a stage, RootLatency) and
    * the conversions' and compare's rounder and output registered. Left names the operator
    * whose single stage is longer than a period allows. */
  def atClock(mhz: Double): Either[String, ScpuConfig] = {
    require(mhz > 0, s"ScpuConfig $name: a clock must be above 0 MHz, got $mhz")
    def need(op: String, e: Either[Double, Int]) = e.left.map(worst =>
      f"SCPU $name at $mhz%.1f MHz on ${family.name}: $op has a stage of $worst%.0f ps (estimated), longer than the ${family.budget(mhz)}%.0f ps a period leaves")
    def rootLat(op: RootOp, alg: RootAlgorithm) = RootCoreSelect.cuts(op, format.sigBits, alg) + 7
    for {
      add <- need("FpAdd", FpAdd.latencyFor(params, family, mhz))
      mul <- need("FpMul", FpMul.latencyFor(params, family, mhz))
    } yield copy(addLatency = add, mulLatency = mul, cvtLatency = FpConvert.stages, cmpLatency = 1,
      sqrtLatency = Some(rootLat(RootOp.Sqrt, sqrtAlg)), recipLatency = Some(rootLat(RootOp.Recip, recipAlg)),
      rsqrtLatency = Some(rootLat(RootOp.Rsqrt, rsqrtAlg)), scaleLatency = 5)
  }
}

object ScpuConfig {
  /** Default pipeline depth of a root operator: digit recurrence produces one bit a step, so
    * about a register every 4 steps; Newton-Raphson one register per cut of its core
    * (NewtonRaphsonCore.naturalLatency: after the seed ROM and each multiply) plus the
    * operator's pre-rounding and output registers.
    */
  def defaultRootLatency(f: FloatFormat, alg: RootAlgorithm, op: RootOp): Int = alg match {
    case RootAlgorithm.DigitRecurrence   => (f.sigBits + 5) / 4
    case nr: RootAlgorithm.NewtonRaphson => NewtonRaphsonCore.naturalLatency(op, nr) + 2
  }

  /** The Newton-Raphson setting the fp32 NR preset uses: 8-bit seeds, two iterations, faithful
    * (< 1 ulp) for sqrt, recip and rsqrt at 24 bits per docs/fp/newton-raphson.md. */
  val nrFp32: RootAlgorithm = RootAlgorithm.NewtonRaphson(8, 2)

  val fp32: ScpuConfig        = ScpuConfig()
  val fp32RsqrtDr: ScpuConfig = fp32.copy(name = "fp32-rsqrt-dr", distance = DistanceMethod.Rsqrt)
  val fp32Nr: ScpuConfig      = fp32.copy(name = "fp32-nr", sqrtAlg = nrFp32, recipAlg = nrFp32, rsqrtAlg = nrFp32)
  val fp32Robust: ScpuConfig  = fp32.copy(name = "fp32-robust", distance = DistanceMethod.Robust)
  val fp64: ScpuConfig        = fp32.copy(name = "fp64", format = FloatFormat.fp64, mulLatency = 2)
  val fp24: ScpuConfig        = fp32.copy(name = "fp24", format = FloatFormat.fp24)
  val fp16: ScpuConfig        = fp32.copy(name = "fp16", format = FloatFormat.fp16)
  val bf16: ScpuConfig        = fp32.copy(name = "bf16", format = FloatFormat.bf16)
  val fp16Robust: ScpuConfig  = fp16.copy(name = "fp16-robust", distance = DistanceMethod.Robust)
  /** fp32 with every operator pipelined for 200 MHz on Cyclone V (atClock: add 12, mul 8, the
    * roots 32; 136 cycles): the default AFU's SCPU. */
  val fp32At200: ScpuConfig   = fp32.atClock(200).fold(e => throw new IllegalStateException(e), identity).copy(name = "fp32-200")

  val all: Seq[ScpuConfig] = Seq(fp32, fp32RsqrtDr, fp32Nr, fp32Robust, fp64, fp24, fp16, bf16, fp16Robust, fp32At200)
  val presets: Map[String, ScpuConfig] = all.map(c => c.name -> c).toMap
  val default: ScpuConfig = fp32

  /** Parses `preset[:key=value]*`, e.g. `fp16-robust`, `fp32:rm=rtz:sqrt=nr8x2:add=2`.
    * Keys: format (fp16, e8m24, "8,24"), rm (RNE, RTZ, RDN, RUP, RMM), subnormals (on/off),
    * distance (sqrt-recip, rsqrt, robust), sqrt/recip/rsqrt (dr, nr<seed>x<iters>), roots (all
    * three), cvt/add/mul/cmp/scale/sqrtLat/recipLat/rsqrtLat (latencies), tag (tag bits),
    * family (cyclonev, arriav, ecp5), mhz (every latency derived for that clock: atClock; a
    * latency given after it overrides it, as options apply in order).
    * A changed preset keeps the preset's name followed by the options ("fp32_rm_rtz").
    */
  def parse(s: String): Either[String, ScpuConfig] = {
    val parts = s.trim.split(':').map(_.trim).toList
    val preset = parts.head
    presets.get(preset.toLowerCase).toRight(
      s"SCPU config '$s': unknown preset '$preset' (known: ${all.map(_.name).mkString(", ")})").flatMap { base =>
      val opts = parts.tail
      opts.foldLeft[Either[String, ScpuConfig]](Right(base)) { (acc, opt) =>
        acc.flatMap(c => applyOption(s, c, opt))
      }.flatMap { c =>
        if (opts.isEmpty) Right(c)
        else {
          val nm = (preset.toLowerCase +: opts.map(_.toLowerCase.replaceAll("[^a-z0-9]+", "_"))).mkString("_")
          safely(s)(c.copy(name = nm))
        }
      }
    }
  }

  private def safely(s: String)(c: => ScpuConfig): Either[String, ScpuConfig] =
    try Right(c) catch { case e: IllegalArgumentException => Left(s"SCPU config '$s': ${e.getMessage.stripPrefix("requirement failed: ")}") }

  private def applyOption(s: String, c: ScpuConfig, opt: String): Either[String, ScpuConfig] = {
    val kv = opt.split("=", 2)
    if (kv.length != 2) return Left(s"SCPU config '$s': option '$opt' is not key=value")
    val (k, v) = (kv(0).trim.toLowerCase, kv(1).trim)
    def int: Either[String, Int] = v.toIntOption.toRight(s"SCPU config '$s': option $k needs an integer, got '$v'")
    def ctx[A](e: Either[String, A]) = e.left.map(m => s"SCPU config '$s': $m")
    k match {
      case "format"     => ctx(FloatFormat.parse(v)).flatMap(f => safely(s)(c.copy(format = f)))
      case "rm"         => ctx(RoundingMode.parse(v)).map(r => c.copy(rounding = r))
      case "subnormals" => v.toLowerCase match {
        case "on" | "true" | "1"  => Right(c.copy(subnormals = true))
        case "off" | "false" | "0" => Right(c.copy(subnormals = false))
        case _ => Left(s"SCPU config '$s': subnormals must be on or off, got '$v'")
      }
      case "distance" => ctx(DistanceMethod.parse(v)).map(d => c.copy(distance = d))
      case "sqrt"     => ctx(RootAlgorithm.parse(v)).map(a => c.copy(sqrtAlg = a))
      case "recip"    => ctx(RootAlgorithm.parse(v)).map(a => c.copy(recipAlg = a))
      case "rsqrt"    => ctx(RootAlgorithm.parse(v)).map(a => c.copy(rsqrtAlg = a))
      case "roots"    => ctx(RootAlgorithm.parse(v)).map(a => c.copy(sqrtAlg = a, recipAlg = a, rsqrtAlg = a))
      case "cvt"      => int.flatMap(n => safely(s)(c.copy(cvtLatency = n)))
      case "add"      => int.flatMap(n => safely(s)(c.copy(addLatency = n)))
      case "mul"      => int.flatMap(n => safely(s)(c.copy(mulLatency = n)))
      case "cmp"      => int.flatMap(n => safely(s)(c.copy(cmpLatency = n)))
      case "scale"    => int.flatMap(n => safely(s)(c.copy(scaleLatency = n)))
      case "sqrtlat"  => int.flatMap(n => safely(s)(c.copy(sqrtLatency = Some(n))))
      case "reciplat" => int.flatMap(n => safely(s)(c.copy(recipLatency = Some(n))))
      case "rsqrtlat" => int.flatMap(n => safely(s)(c.copy(rsqrtLatency = Some(n))))
      case "tag"      => int.flatMap(n => safely(s)(c.copy(tagBits = n)))
      case "link"     => ctx(FloatFormat.parse(v)).flatMap(f => safely(s)(c.copy(link = Some(f))))
      case "family"   => ctx(FpgaFamily.parse(v)).map(fam => c.copy(family = fam))
      case "mhz"      => v.toDoubleOption.filter(_ > 0).toRight(s"SCPU config '$s': option mhz needs a clock above 0 (MHz), got '$v'")
        .flatMap(m => ctx(c.atClock(m)))
      case _ => Left(s"SCPU config '$s': unknown option '$k' (format, rm, subnormals, distance, sqrt, recip, rsqrt, roots, cvt, add, mul, cmp, scale, sqrtLat, recipLat, rsqrtLat, tag, link, family, mhz)")
    }
  }
}
