package collide.formal

import collide.testutil.Slow

import collide.afu._

class ReadEngineFormalSpec extends FormalSpecKit {
  behavior of "ReadEngine (formal: 2 tags, a 2-line pair buffer, 8-line sphere table)"

  private val p = PucParams(scpus = 1, linkWidth = 16, scpuTagBits = 24, scpuLatency = 1, maxSpheres = 64,
    maxReads = 2, maxWrites = 2, tagBits = 1, name = "_formal")
  private val depth = FormalSpecKit.depth("ReadEngine", 8)

  it should "issue only free tags, read line k of each table k-th, and route every response by its tag, for 6 cycles" in {
    prove("ReadEngine r=2", 6)(new ReadEngineFormal(p))
  }
  it should "issue only free tags, read line k of each table k-th, and route every response by its tag, for the full bound" taggedAs Slow in {
    prove("ReadEngine r=2", depth)(new ReadEngineFormal(p))
  }
  it should "reach every sphere line in and every pair line out with nothing in flight" in {
    refute("ReadEngine r=2 reach", depth)(new ReadEngineFormal(p, Check.Reach))
  }
  it should "fail the proof when the wrapper misses the request of tag 1 (seeded bug)" in {
    refute("ReadEngine r=2 seeded bug", depth)(new ReadEngineFormal(p, Check.SeededBug))
  }
}
