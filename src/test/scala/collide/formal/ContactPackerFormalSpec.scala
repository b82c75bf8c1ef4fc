package collide.formal

class ContactPackerFormalSpec extends FormalSpecKit {
  behavior of "ContactPacker (formal: compact mode, 2 records a line)"

  private val p = FormalParams.records
  private val depth = FormalSpecKit.depth("ContactPacker", 8)

  provenQuickAndSlow("write line k as the k-th line, each record in its slot once, and every line below the capacity",
    "ContactPacker R=2", 5, depth)(new ContactPackerFormal(p))
  it should "reach flushed and empty after two lines with the watched record among them" in {
    refute("ContactPacker R=2 reach", depth)(new ContactPackerFormal(p, Check.Reach))
  }
  it should "fail the proof when the wrapper counts a full cycle's records twice (seeded bug)" in {
    refute("ContactPacker R=2 seeded bug", depth)(new ContactPackerFormal(p, Check.SeededBug))
  }
}
