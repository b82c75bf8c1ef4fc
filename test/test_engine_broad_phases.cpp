// Other engines' broad phases as `collide spheres` backends (world/bullet_broad_phase.hpp,
// world/fcl_broad_phase.hpp): their candidates through the simd kernel give simd's contacts
// byte for byte on the shared random worlds (printed, settable seeds) and the grid's corner
// cases; where an engine's own narrow phase decides differently from binary32, the tests pin
// how (Bullet's: never, FCL's binary64 test: grazing pairs only). ODE's quadtree space gives
// the same contacts as its sweep and prune, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "support/random_world.hpp"
#include "support/test_seed.hpp"
#include "support/world_cases.hpp"
#include "support/world_compare.hpp"
#include "world/engine_broad_phase.hpp"
#include "world/ode_space_broad_phase.hpp"
#include "world/world_collider.hpp"
#if COLLIDE_HAVE_BULLET
#include "world/bullet_broad_phase.hpp"
#endif
#if COLLIDE_HAVE_FCL
#include "world/fcl_broad_phase.hpp"
#endif

using namespace collide;
using namespace collide::world;

namespace {

struct EngineRun {
  WorldContacts w;
  PairList engine;  // the engine's own contacts on the same candidates
};

EngineRun collideWith(EngineBroadPhase& broad, const SphereTable& t) {
  SimdBackend simd;
  WorldCollider wc(broad, simd);
  EngineRun r;
  WorldTiming time;
  wc.collide(t, r.w, time);
  broad.engineContacts(t, r.engine);
  return r;
}

using Factory = std::function<std::unique_ptr<EngineBroadPhase>()>;

// Every world of test_tuned_grid, twice with fresh seeds, and the corner cases: simd's bytes.
void expectSimdsContacts(const std::string& engine, const Factory& make, std::uint64_t seed) {
  std::vector<test::WorldCase> cases = test::cornerWorldCases();
  for (int round = 0; round < 2; ++round)
    for (auto& c : test::randomWorldCases(seed + 100 * round)) {
      c.name += ", round " + std::to_string(round);
      cases.push_back(std::move(c));
    }
  auto broad = make();  // one object for every world, as --repeat reuses it
  for (const auto& c : cases) {
    const WorldContacts want = test::simdContacts(c.spheres);
    const EngineRun got = collideWith(*broad, c.spheres);
    test::expectSame(want, got.w, engine + ", " + c.name);
    EXPECT_GE(got.w.candidates, got.w.pairs.size()) << engine << ", " << c.name;
  }
}

// The engine's own decision against binary32 on the random worlds: the pairs only one of them
// calls a contact, each checked by `allowed`, and their count returned.
std::size_t engineDifferences(const Factory& make, std::uint64_t seed,
                              const std::function<void(const SphereTable&, std::uint32_t, std::uint32_t)>& allowed) {
  std::size_t differ = 0;
  auto broad = make();
  for (const auto& c : test::randomWorldCases(seed)) {
    const EngineRun r = collideWith(*broad, c.spheres);
    std::vector<std::uint64_t> a, b;
    for (std::size_t k = 0; k < r.engine.size(); ++k) a.push_back((std::uint64_t{r.engine.i[k]} << 32) | r.engine.j[k]);
    for (std::size_t k = 0; k < r.w.pairs.size(); ++k) b.push_back((std::uint64_t{r.w.pairs.i[k]} << 32) | r.w.pairs.j[k]);
    std::sort(a.begin(), a.end());
    EXPECT_TRUE(std::adjacent_find(a.begin(), a.end()) == a.end()) << c.name << ": a pair twice";
    std::vector<std::uint64_t> d;
    std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(d));
    const EngineDiff diff = compareContacts(r.engine, r.w.pairs);
    EXPECT_EQ(diff.onlyEngine + diff.onlyExact, d.size()) << c.name;
    for (auto k : d) allowed(c.spheres, static_cast<std::uint32_t>(k >> 32), static_cast<std::uint32_t>(k));
    std::cout << "[ engine   ] " << c.name << ": " << r.engine.size() << " engine contacts, " << r.w.pairs.size()
              << " binary32 contacts, " << diff.onlyEngine << " only the engine's, " << diff.onlyExact
              << " only binary32's\n";
    differ += d.size();
  }
  return differ;
}

// |d - (r1 + r2)| within a few binary32 ulps of r1 + r2 + d: a grazing pair, where binary32 and
// binary64 may round apart.
void expectGrazing(const SphereTable& t, std::uint32_t i, std::uint32_t j) {
  const double dx = t.x[i] - t.x[j], dy = t.y[i] - t.y[j], dz = t.z[i] - t.z[j];
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz), reach = t.r[i] + t.r[j];
  EXPECT_LE(std::abs(d - reach), 8 * 0x1p-24 * (reach + d)) << "pair " << i << ", " << j << " is no grazing pair";
}

}  // namespace

#if COLLIDE_HAVE_BULLET
TEST(EngineBroadPhases, BulletDbvtGivesSimdsContacts) {
  expectSimdsContacts("bullet dbvt", [] { return std::make_unique<BulletBroadPhase>(BulletBroadKind::Dbvt); },
                      test::testSeed(4801));
}
TEST(EngineBroadPhases, BulletAxisSweepGivesSimdsContacts) {
  expectSimdsContacts("bullet sap", [] { return std::make_unique<BulletBroadPhase>(BulletBroadKind::AxisSweep); },
                      test::testSeed(4802));
}
// Past 32,766 spheres the axis sweep takes 32-bit handles (bt32BitAxisSweep3); here past 1,000.
// (Bullet's axis sweep inserts each handle by moving its edges into place: a world built from
// scratch costs O(n^2), 16 s for 33,000 spheres here, so the switch is lowered for the test.)
TEST(EngineBroadPhases, BulletWideAxisSweepGivesSimdsContacts) {
  const std::uint64_t seed = test::testSeed(4803);
  BulletBroadPhase sap(BulletBroadKind::AxisSweep, 1000);
  for (const auto& c : test::randomWorldCases(seed)) {
    const EngineRun got = collideWith(sap, c.spheres);
    EXPECT_NE(sap.name().find("bt32BitAxisSweep3"), std::string::npos) << sap.name();
    test::expectSame(test::simdContacts(c.spheres), got.w, "32-bit handles, " + c.name);
  }
}
// Bullet's sphere algorithm is binary32 too (btScalar is float in Debian's build) and uses the
// same rule, |c1 - c2| > r1 + r2 being no contact: its manifolds hold exactly our contacts.
TEST(EngineBroadPhases, BulletsOwnNarrowPhaseAgreesWithBinary32) {
  const std::uint64_t seed = test::testSeed(4804);
  for (auto kind : {BulletBroadKind::Dbvt, BulletBroadKind::AxisSweep}) {
    const std::size_t differ = engineDifferences([kind] { return std::make_unique<BulletBroadPhase>(kind); }, seed,
                                                 [](const SphereTable& t, std::uint32_t i, std::uint32_t j) {
                                                   ADD_FAILURE() << "Bullet and binary32 differ on " << i << ", " << j;
                                                   expectGrazing(t, i, j);
                                                 });
    EXPECT_EQ(differ, 0u) << toString(kind);
  }
}
#else
TEST(EngineBroadPhases, Bullet) { GTEST_SKIP() << "this build has no Bullet (CMake found no pkg-config bullet): --backend bullet is not built"; }
#endif

#if COLLIDE_HAVE_FCL
TEST(EngineBroadPhases, FclDynamicTreeGivesSimdsContacts) {
  expectSimdsContacts("fcl tree", [] { return std::make_unique<FclBroadPhase>(FclManagerKind::DynamicTree); },
                      test::testSeed(4811));
}
TEST(EngineBroadPhases, FclSweepAndPruneGivesSimdsContacts) {
  expectSimdsContacts("fcl sap", [] { return std::make_unique<FclBroadPhase>(FclManagerKind::SweepAndPrune); },
                      test::testSeed(4812));
}
TEST(EngineBroadPhases, FclSpatialHashGivesSimdsContacts) {
  expectSimdsContacts("fcl hash", [] { return std::make_unique<FclBroadPhase>(FclManagerKind::SpatialHash); },
                      test::testSeed(4813));
}
// FCL decides in binary64: it differs from binary32 on grazing pairs only (the touching pairs
// nudged by ulps that the worlds hold), and on some of them it does.
TEST(EngineBroadPhases, FclsOwnNarrowPhaseDiffersOnGrazingPairsOnly) {
  const std::uint64_t seed = test::testSeed(4814);
  const std::size_t differ =
      engineDifferences([] { return std::make_unique<FclBroadPhase>(FclManagerKind::DynamicTree); }, seed, expectGrazing);
  std::cout << "[ engine   ] fcl::collide and binary32 differ on " << differ << " grazing pairs\n";
  EXPECT_GT(differ, 0u) << "the worlds' ulp-nudged touching pairs should split binary32 and binary64";
}
#else
TEST(EngineBroadPhases, Fcl) { GTEST_SKIP() << "this build has no FCL (CMake found no package fcl): --backend fcl is not built"; }
#endif

// ODE's quadtree: the same contacts as its sweep and prune, bit for bit (ODE's own decision,
// dCollide in binary64, on either space's pairs), on the random and corner worlds.
TEST(EngineBroadPhases, OdeQuadTreeGivesTheContactsOfOdeSweepAndPrune) {
  const std::uint64_t seed = test::testSeed(4821);
  std::vector<test::WorldCase> cases = test::cornerWorldCases();
  for (auto& c : test::randomWorldCases(seed)) cases.push_back(std::move(c));
  OdeSpaceBroadPhase quad(OdeSpaceKind::QuadTree), sap(OdeSpaceKind::SweepAndPrune);
  for (const auto& c : cases) {
    auto run = [&](OdeSpaceBroadPhase& space) {
      OdeBackend ode;
      const OdeGeomBinding geoms(&ode, space.geoms());
      WorldCollider wc(space, ode);
      WorldContacts w;
      WorldTiming time;
      wc.collide(c.spheres, w, time);
      return w;
    };
    const WorldContacts want = run(sap);
    test::expectSame(want, run(quad), "ode quadtree, " + c.name);
  }
}

TEST(EngineBroadPhases, OdeQuadTreeDepth) {
  EXPECT_EQ(OdeSpaceBroadPhase::quadTreeDepth(10, 100, 0.5), 1);       // few spheres: one split
  EXPECT_EQ(OdeSpaceBroadPhase::quadTreeDepth(65536, 1000, 0.5), 6);   // 4^6 = 4096 <= 8192 < 4^7
  EXPECT_EQ(OdeSpaceBroadPhase::quadTreeDepth(65536, 40, 0.5), 3);     // 40 / 2^4 = 2.5 < 4 diameters
  EXPECT_EQ(OdeSpaceBroadPhase::quadTreeDepth(1u << 30, 1e9, 1), 10);  // at most 10
}
