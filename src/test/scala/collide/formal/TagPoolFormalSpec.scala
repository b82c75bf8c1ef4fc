package collide.formal

import collide.testutil.Slow

class TagPoolFormalSpec extends FormalSpecKit {
  behavior of "TagPool (formal: 4 tags)"
  private val depth = FormalSpecKit.depth("TagPool", 10)
  it should "hand out only free tags below n and count the tags in flight, for the bound" taggedAs Slow in {
    prove("TagPool n=4", depth)(new TagPoolFormal(4, 2))
  }
  it should "get every tag in flight at once and all of them back" taggedAs Slow in {
    refute("TagPool n=4 reach", depth)(new TagPoolFormal(4, 2, Check.Reach))
  }
  it should "fail the proof when the wrapper misses the take of tag 0 (seeded bug)" taggedAs Slow in {
    refute("TagPool n=4 seeded bug", depth)(new TagPoolFormal(4, 2, Check.SeededBug))
  }
}
