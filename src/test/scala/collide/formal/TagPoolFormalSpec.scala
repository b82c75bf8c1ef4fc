package collide.formal

class TagPoolFormalSpec extends FormalSpecKit {
  behavior of "TagPool (formal: 4 tags)"
  private val depth = FormalSpecKit.depth("TagPool", 20)
  it should "hand out only free tags below n and count the tags in flight, for the bound" in {
    prove("TagPool n=4", depth)(new TagPoolFormal(4, 2))
  }
  it should "get every tag in flight at once and all of them back" in {
    refute("TagPool n=4 reach", depth)(new TagPoolFormal(4, 2, Check.Reach))
  }
  it should "fail the proof when the wrapper misses the take of tag 0 (seeded bug)" in {
    refute("TagPool n=4 seeded bug", depth)(new TagPoolFormal(4, 2, Check.SeededBug))
  }
}
