// Scala 2.13.15 / Chisel 6.7.0 / chiseltest 6.0.0 (docs/conventions.md, "Tools"):
// chiseltest is frozen at 6.0.0, so Chisel stays on 6.x.
ThisBuild / scalaVersion := "2.13.15"
ThisBuild / version      := "0.1.0"
ThisBuild / organization := "io.github.collide"

val chiselVersion = "6.7.0"

// Seconds each heavy spec took in a clean-clone run (2 cores, two JVMs): the weights of the
// two test groups below (bench/results/suite).
val suiteSeconds = Map(
  "BroadPhaseSpec" -> 284, "AfuWorldSpec" -> 275, "PucSpec" -> 200, "AfuSpec" -> 88,
  "ScpuSpec" -> 131, "FpAddSpec" -> 67, "SphereKeysSpec" -> 77, "ChunkMatcherSpec" -> 58,
  "FpRsqrtSpec" -> 53, "GeneratedFreshSpec" -> 47, "FpRecipSpec" -> 31, "ContactPackerFormalSpec" -> 43,
  "FpSqrtSpec" -> 37, "BucketSortSpec" -> 24, "FpMulSpec" -> 40, "ReadEngineFormalSpec" -> 23,
  "ContactCollectorSpec" -> 10, "WorldPairLinesSpec" -> 16, "ChunkMatcherFormalSpec" -> 18,
  "BroadPhaseModelSpec" -> 14, "NewtonRaphsonCoreSpec" -> 14, "NewtonRaphsonErrorSpec" -> 7,
  "FpConvertSpec" -> 12, "TagPoolFormalSpec" -> 11, "BucketSortFormalSpec" -> 14, "SpherePlaneSpec" -> 25, "CapsuleSphereSpec" -> 35)

// sbt's default allows one forked test group at a time; the two groups below run together.
Global / concurrentRestrictions := Seq(
  Tags.limitAll(java.lang.Runtime.getRuntime.availableProcessors.max(2)),
  Tags.limit(Tags.ForkedTestGroup, 2),
  Tags.exclusiveGroup(Tags.Clean))

lazy val root = (project in file("."))
  .settings(
    name := "collide-accel",
    libraryDependencies ++= Seq(
      "org.chipsalliance" %% "chisel"     % chiselVersion,
      "edu.berkeley.cs"   %% "chiseltest" % "6.0.0" % Test,
      // scopt: the generator CLI's flags and --help, instead of a hand-written parser.
      "com.github.scopt"  %% "scopt"      % "4.1.0",
      // ujson: manifests and report files, instead of hand-built JSON strings.
      "com.lihaoyi"       %% "ujson"      % "3.3.1"
    ),
    addCompilerPlugin("org.chipsalliance" % "chisel-plugin" % chiselVersion cross CrossVersion.full),
    scalacOptions ++= Seq("-language:reflectiveCalls", "-deprecation", "-feature", "-Xcheckinit", "-Ymacro-annotations"),
    Test / fork := true,
    // Two forked JVMs run the specs at once, so on a 2-core machine one simulates while the
    // other builds its Verilator model. Suites go to the lighter group, heaviest first, by
    // about how many seconds each took in CI (suiteSeconds; unlisted ones count 10). Within a
    // JVM, suites run one at a time.
    Test / testGrouping := {
      // The formal specs (src/test/scala/collide/formal, docs/formal.md) run chiseltest's bounded
      // checks with Yices 2, which tools/setup.sh puts in tools/.cache/smt: first on the test JVMs' PATH.
      val smtDir = baseDirectory.value / "tools" / ".cache" / "smt"
      val path = (smtDir.getAbsolutePath +: sys.env.get("PATH").toSeq).mkString(java.io.File.pathSeparator)
      // chiseltest compiles a Verilator model with make and Verilator's defaults (g++, -Os for
      // the model's hot code, after any VerilatorCFlags): for the suite's short runs that is
      // most of a case's time. Make takes variables from MAKEFLAGS as if given on its command
      // line, so the test JVMs' builds compile at -O0, with clang++ where it is installed
      // (tools/setup.sh installs it): a third of the build's CPU time (bench/results/suite).
      val clang = sys.env.getOrElse("PATH", "").split(java.io.File.pathSeparator).exists(d => new java.io.File(d, "clang++").canExecute)
      val makeFlags = (sys.env.get("MAKEFLAGS").toSeq ++ Seq("OPT_FAST=-O0 OPT_SLOW=-O0 OPT_GLOBAL=-O0") ++
        (if (clang) Seq("CXX=clang++\\ -Wno-unused-command-line-argument") else Nil)).mkString(" ")
      val opts = ForkOptions().withRunJVMOptions((Test / javaOptions).value.toVector)
        .withEnvVars(Map("PATH" -> path, "MAKEFLAGS" -> makeFlags))
      def weight(t: TestDefinition) = suiteSeconds.getOrElse(t.name.split('.').last, 10)
      val groups = Array.fill(2)(Vector.empty[TestDefinition]); val load = Array.fill(2)(0)
      for (t <- (Test / definedTests).value.sortBy(t => (-weight(t), t.name))) {
        val g = if (load(0) <= load(1)) 0 else 1
        groups(g) :+= t; load(g) += weight(t)
      }
      groups.toSeq.zipWithIndex.collect { case (ts, i) if ts.nonEmpty => Tests.Group(s"specs-$i", ts, Tests.SubProcess(opts)) }
    },
    Test / parallelExecution := true,
    Test / testForkedParallel := false,
    Test / javaOptions ++= Seq("-Xss8m", "-Xmx6g"),
    // Tests run in a forked JVM: forward the replay knobs (collide.testutil.Seeds) and -Dvcd (AfuSpec).
    Test / javaOptions ++= Seq("seed", "scale", "vcd").flatMap(k => sys.props.get(k).map(v => s"-D$k=$v")),
    run / fork := true,
    // `sbt "run ..."` is the generator CLI
    Compile / run / mainClass := Some("collide.Generate"),
    run / javaOptions ++= Seq("-Xss8m", "-Xmx4g"),
    Test / testOptions += Tests.Argument(TestFrameworks.ScalaTest, "-oD")
  )
