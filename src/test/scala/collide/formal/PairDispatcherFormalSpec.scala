package collide.formal

class PairDispatcherFormalSpec extends FormalSpecKit {
  behavior of "PairDispatcher (formal: 2 SCPUs, 16-pair lines)"

  private val p = FormalParams.dispatcher
  private val depth = FormalSpecKit.depth("PairDispatcher", 8)

  it should "dispatch every pair it accepts at most once, and every one by the time it is idle" in {
    prove("PairDispatcher n=2", depth)(new PairDispatcherFormal(p))
  }
  it should "reach a drained state with the watched pair in and dispatched" in {
    refute("PairDispatcher n=2 reach", depth)(new PairDispatcherFormal(p, Check.Reach))
  }
  it should "fail the proof when the wrapper misses the groups whose first pair has bit 1 set (seeded bug)" in {
    refute("PairDispatcher n=2 seeded bug", depth)(new PairDispatcherFormal(p, Check.SeededBug))
  }
}
