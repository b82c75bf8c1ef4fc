package collide.afu

import org.scalatest.flatspec.AnyFlatSpec
import collide.Generate

/** The generator's options as docs/afu.md's "Generator CLI" names them: each flag the parser
  * takes is described there, and each flag named there is one the parser takes, so the two
  * cannot drift apart. */
class GeneratorDocsSpec extends AnyFlatSpec {
  behavior of "docs/afu.md's Generator CLI section"

  private val flag = """--([a-z][a-z0-9-]*[a-z0-9])""".r
  private def flags(text: String): Set[String] = flag.findAllMatchIn(text).map(_.group(1)).toSet

  /** The parser's long options, from its own usage text (what `--help` prints). */
  private val parserFlags = flags(scopt.OParser.usage(Generate.parser))

  /** The section's text: from its heading to the next heading of the same level. */
  private val section: String = {
    val doc = scala.io.Source.fromFile("docs/afu.md", "UTF-8")
    val text = try doc.mkString finally doc.close()
    val start = text.indexOf("\n## Generator CLI")
    assert(start >= 0, "docs/afu.md has no \"## Generator CLI\" section")
    val end = text.indexOf("\n## ", start + 1)
    text.substring(start, if (end < 0) text.length else end)
  }

  it should "describe every option the generator's parser takes" in {
    assert(parserFlags.size > 20, s"the usage text should list the options: $parserFlags")
    val missing = (parserFlags - "help").diff(flags(section))
    assert(missing.isEmpty, s"options the parser takes that docs/afu.md's Generator CLI does not describe: ${missing.toSeq.sorted.mkString(", ")}")
  }

  /** Flags the section names that are not the generator's: the error format's placeholder
    * (`error: --flag: problem`) and firtool's option the generator passes on. */
  private val notTheGenerators = Set("flag", "lowering-options")

  it should "name no option the parser does not take" in {
    val unknown = flags(section).diff(parserFlags + "help" ++ notTheGenerators)
    assert(unknown.isEmpty, s"docs/afu.md's Generator CLI names options the parser does not take: ${unknown.toSeq.sorted.mkString(", ")}")
  }
}
