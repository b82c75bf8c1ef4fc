package collide.formal

class ContactCollectorFormalSpec extends FormalSpecKit {
  behavior of "ContactCollector (formal: dense mode, 2 SCPUs, 2 records a line)"

  private val p = FormalParams.records
  // Proven to 12 in 3 s and to 16 in 62 s; 20 did not finish in 5 minutes.
  private val depth = FormalSpecKit.depth("ContactCollector", 12)

  provenQuickAndSlow("write no more records than room and count each group's pairs once its records have gone",
    "ContactCollector n=2", depth, 16)(new ContactCollectorFormal(p))
  it should "reach two groups counted with every record out" in {
    refute("ContactCollector reach", depth + 2)(new ContactCollectorFormal(p, Check.Reach))
  }
  it should "fail the proof when the wrapper counts a full cycle's records twice (seeded bug)" in {
    refute("ContactCollector seeded bug", depth)(new ContactCollectorFormal(p, Check.SeededBug))
  }
}
