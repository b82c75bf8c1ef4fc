package chiseltest.formal.backends

/** chiseltest 6.0.0 keeps its engine annotations other than z3 package-private; the formal
  * specs (collide.formal) choose theirs by name through this one accessor. */
object Engines {
  def byName(name: String): FormalEngineAnnotation = name match {
    case "z3"       => Z3EngineAnnotation
    case "yices2"   => Yices2EngineAnnotation
    case "bitwuzla" => BitwuzlaEngineAnnotation
    case "btormc"   => BtormcEngineAnnotation
    case other      => throw new IllegalArgumentException(s"FORMAL_ENGINE=$other: expected z3, yices2, bitwuzla or btormc")
  }
}
