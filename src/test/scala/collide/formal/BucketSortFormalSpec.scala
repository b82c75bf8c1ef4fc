package collide.formal

/** Two items, four buckets in two counter words, one sort port (two make the entries a
  * read-write RAM port, which chiseltest's formal backend does not take). A full world with
  * both items in the watched bucket is sorted and checked 26 cycles after reset when every
  * offer is taken at once (its Reach witness); the Slow proof leaves two cycles of stalls on
  * top (docs/formal.md). */
class BucketSortFormalSpec extends FormalSpecKit {
  behavior of "BucketSort (formal: 2 items, 4 buckets, 1 port)"
  private val depth = FormalSpecKit.depth("BucketSort", 26)
  private def sort(check: Check) = new BucketSortFormal(items = 2, bucketsLog2 = 2, wordLog2 = 1, ports = 1, check)
  provenQuickAndSlow("sort every world of up to two items stably into its buckets, each item counted and placed once",
    "BucketSort n=2 p=1", depth, 28)(sort(Check.Prove))
  it should "sort a full world with both items in the watched bucket" in {
    refute("BucketSort n=2 p=1 reach", depth)(sort(Check.Reach))
  }
  it should "fail the proof when the wrapper drops item 0 in the scatter pass (seeded bug)" in {
    refute("BucketSort n=2 p=1 seeded bug", depth)(sort(Check.SeededBug))
  }
}
