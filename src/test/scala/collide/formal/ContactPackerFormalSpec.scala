package collide.formal

import collide.testutil.Slow

import collide.afu._

class ContactPackerFormalSpec extends FormalSpecKit {
  behavior of "ContactPacker (formal: compact mode, 2 records a line)"

  private val p = PucParams(scpus = 2, linkWidth = 32, scpuTagBits = 24, scpuLatency = 1, maxSpheres = 64,
    maxReads = 2, maxWrites = 2, tagBits = 1, records = RecordLayout.Full, name = "_formal")
  private val depth = FormalSpecKit.depth("ContactPacker", 8)

  it should "write line k as the k-th line, each record in its slot once, and every line below the capacity, for 5 cycles" in {
    prove("ContactPacker R=2", 5)(new ContactPackerFormal(p))
  }
  it should "write line k as the k-th line, each record in its slot once, and every line below the capacity, for the full bound" taggedAs Slow in {
    prove("ContactPacker R=2", depth)(new ContactPackerFormal(p))
  }
  it should "reach flushed and empty after two lines with the watched record among them" in {
    refute("ContactPacker R=2 reach", depth)(new ContactPackerFormal(p, Check.Reach))
  }
  it should "fail the proof when the wrapper counts a full cycle's records twice (seeded bug)" in {
    refute("ContactPacker R=2 seeded bug", depth)(new ContactPackerFormal(p, Check.SeededBug))
  }
}
