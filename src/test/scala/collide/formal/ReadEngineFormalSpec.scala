package collide.formal

class ReadEngineFormalSpec extends FormalSpecKit {
  behavior of "ReadEngine (formal: 2 tags, a 2-line pair buffer, 8-line sphere table)"

  private val p = FormalParams.reader
  private val depth = FormalSpecKit.depth("ReadEngine", 8)

  provenQuickAndSlow("issue only free tags, read line k of each table k-th, and route every response by its tag",
    "ReadEngine r=2", 6, depth)(new ReadEngineFormal(p))
  it should "reach every sphere line in and every pair line out with nothing in flight" in {
    refute("ReadEngine r=2 reach", depth)(new ReadEngineFormal(p, Check.Reach))
  }
  it should "fail the proof when the wrapper misses the request of tag 1 (seeded bug)" in {
    refute("ReadEngine r=2 seeded bug", depth)(new ReadEngineFormal(p, Check.SeededBug))
  }
}
