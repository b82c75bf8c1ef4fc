package collide.testutil

import chiseltest.internal.CachingAnnotation
import chiseltest.simulator.VerilatorBackendAnnotation
import firrtl2.AnnotationSeq
import firrtl2.options.TargetDirAnnotation

/** Verilator builds shared by the cases of one spec that test one design.
  *
  * chiseltest's CachingAnnotation reuses a model when the circuit's hash matches the one saved
  * in the test's target directory, but that directory is named after the test case: on a
  * clean clone every case builds its own model, even where five cases test one design.
  * `verilator(spec, design)` gives each (spec, design) one directory, so the first case builds
  * and the others reuse the build (the hash still guards against a changed circuit). Cases of
  * one spec run one at a time, so no two builds share a directory at once. `design` names the
  * configuration (an AfuConfig's id, say): two designs must never share a name.
  */
object Builds {
  def verilator(spec: String, design: String): AnnotationSeq =
    Seq(VerilatorBackendAnnotation, CachingAnnotation, TargetDirAnnotation(s"test_run_dir/$spec/$design"))
}
