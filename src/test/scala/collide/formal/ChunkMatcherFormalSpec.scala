package collide.formal

import collide.testutil.Slow

class ChunkMatcherFormalSpec extends FormalSpecKit {
  behavior of "ChunkMatcher (formal: a 2-sphere chunk with a 2-sphere hit queue against none)"
  // Proven to 6 (15 s); 10 did not finish in 8 minutes. The finish needs 7 cycles.
  private val depth = FormalSpecKit.depth("ChunkMatcher", 6)

  it should "put out the same pairs in the same order with its hit queue as without, for the bound" in {
    prove("ChunkMatcher h=2 vs h=0", depth)(new ChunkMatcherFormal())
  }
  // (the witness is 8 cycles long: 152 s)
  it should "reach two pairs compared with both matchers idle" taggedAs Slow in {
    refute("ChunkMatcher reach", depth + 2)(new ChunkMatcherFormal(check = Check.Reach))
  }
  it should "fail the proof when the wrapper drops the queued matcher's pairs with index 0 (seeded bug)" in {
    refute("ChunkMatcher seeded bug", depth)(new ChunkMatcherFormal(check = Check.SeededBug))
  }
}
