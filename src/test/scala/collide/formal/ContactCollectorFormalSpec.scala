package collide.formal

import collide.testutil.Slow

import collide.afu._

class ContactCollectorFormalSpec extends FormalSpecKit {
  behavior of "ContactCollector (formal: dense mode, 2 SCPUs, 2 records a line)"

  private val p = PucParams(scpus = 2, linkWidth = 32, scpuTagBits = 24, scpuLatency = 1, maxSpheres = 64,
    maxReads = 2, maxWrites = 2, tagBits = 1, records = RecordLayout.Full, name = "_formal")
  // Proven to 12 in 3 s and to 16 in 62 s; 20 did not finish in 5 minutes.
  private val depth = FormalSpecKit.depth("ContactCollector", 12)

  it should "write no more records than room and count each group's pairs once its records have gone" in {
    prove("ContactCollector n=2", depth)(new ContactCollectorFormal(p))
  }
  it should "write no more records than room and count each group's pairs once its records have gone, for 16 cycles" taggedAs Slow in {
    prove("ContactCollector n=2", 16)(new ContactCollectorFormal(p))
  }
  it should "reach two groups counted with every record out" in {
    refute("ContactCollector reach", depth + 2)(new ContactCollectorFormal(p, Check.Reach))
  }
  it should "fail the proof when the wrapper counts a full cycle's records twice (seeded bug)" in {
    refute("ContactCollector seeded bug", depth)(new ContactCollectorFormal(p, Check.SeededBug))
  }
}
