// Scala 2.13.15 / Chisel 6.7.0 / chiseltest 6.0.0 (docs/conventions.md, "Tools"):
// chiseltest is frozen at 6.0.0, so Chisel stays on 6.x.
ThisBuild / scalaVersion := "2.13.15"
ThisBuild / version      := "0.1.0"
ThisBuild / organization := "io.github.collide"

val chiselVersion = "6.7.0"

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
    Test / parallelExecution := false,
    Test / fork := true,
    Test / javaOptions ++= Seq("-Xss8m", "-Xmx6g"),
    // Tests run in a forked JVM: forward the replay knobs (collide.testutil.Seeds).
    Test / javaOptions ++= Seq("seed", "scale").flatMap(k => sys.props.get(k).map(v => s"-D$k=$v")),
    run / fork := true,
    // `sbt "run ..."` is the generator CLI
    Compile / run / mainClass := Some("collide.Generate"),
    run / javaOptions ++= Seq("-Xss8m", "-Xmx4g"),
    Test / testOptions += Tests.Argument(TestFrameworks.ScalaTest, "-oD")
  )
