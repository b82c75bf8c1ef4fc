// The tuned grid (world/tuned_world.hpp) against `collide spheres --backend simd`
// (world/cpu_world.hpp): the same contacts, values, flags, bad spheres and order, bit for bit,
// on seeded worlds (uniform, clustered, mixed radii, with touching pairs and coincident
// centres added) and at every thread count; and its levels on the corner cases of the grid.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/random_world.hpp"
#include "support/test_seed.hpp"
#include "support/world_cases.hpp"
#include "support/world_compare.hpp"
#include "world/cpu_world.hpp"
#include "world/tuned_world.hpp"

using namespace collide;
using namespace collide::world;

namespace {

using test::addTouchingAndCoincident;
using test::csvOf;
using test::expectSame;
using test::simdContacts;

WorldContacts tunedContacts(const SphereTable& t, unsigned threads, std::vector<TunedLevel>* levels = nullptr) {
  TunedWorld tuned(threads);
  WorldContacts w;
  WorldTiming time;
  tuned.collide(t, w, time);
  if (levels) *levels = tuned.lastLevels();
  return w;
}

}  // namespace

TEST(TunedGrid, GivesTheSimdGridsContactsOnRandomWorlds) {
  const std::uint64_t seed = test::testSeed(4701);
  for (int round = 0; round < 3; ++round)
    for (const auto& c : test::randomWorldCases(seed + 100 * round)) {
      const WorldContacts want = simdContacts(c.spheres);
      std::vector<TunedLevel> levels;
      const WorldContacts got = tunedContacts(c.spheres, 1, &levels);
      expectSame(want, got, c.name + ", round " + std::to_string(round));
      EXPECT_GT(want.pairs.size(), c.spheres.size() / 10) << c.name;  // the worlds do touch
      if (c.name.find("mixed") != std::string::npos) {
        EXPECT_GE(levels.size(), 2u) << c.name << ": large spheres";
      }
    }
}

TEST(TunedGrid, EveryThreadCountWritesTheSameBytes) {
  const std::uint64_t seed = test::testSeed(4702);
  for (const auto& c : test::randomWorldCases(seed)) {
    const std::string want = csvOf(simdContacts(c.spheres));
    for (unsigned threads : {1u, 2u, 3u, 7u}) {
      EXPECT_EQ(want, csvOf(tunedContacts(c.spheres, threads))) << c.name << ", " << threads << " threads";
    }
  }
}

// A large world on several threads: many chunks, so threads interleave their cells.
TEST(TunedGrid, ManyChunksOnSevenThreads) {
  const std::uint64_t seed = test::testSeed(4703);
  test::WorldShape w;
  w.spheres = 40000;
  w.extent = 30;
  SphereTable t = test::randomWorld(seed, w);
  addTouchingAndCoincident(seed + 1, t, 2000);
  const WorldContacts want = simdContacts(t);
  expectSame(want, tunedContacts(t, 7), "7 threads");
  expectSame(want, tunedContacts(t, 1), "1 thread");
}

// The grid's corner cases (those of GridBroadPhase's tests): nothing, one sphere, everything
// at one point, a sphere 50 cells across, many large spheres, negative and denormal centres
// on cell boundaries, tiny radii, and centres 2e6 m apart with tiny radii (the cells are
// widened until the key fits).
TEST(TunedGrid, CornerCases) {
  const std::vector<test::WorldCase> cases = test::cornerWorldCases();
  for (const auto& c : cases) {
    const WorldContacts want = simdContacts(c.spheres);
    for (unsigned threads : {1u, 3u}) expectSame(want, tunedContacts(c.spheres, threads), c.name + ", " + std::to_string(threads) + " threads");
  }
}
