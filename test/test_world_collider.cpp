// World mode on the CPU (world/world_collider.hpp): each pipeline gives every contact of its
// narrow phase over all pairs, bit for bit; ODE's two spaces agree bit for bit; simd (binary32)
// and ode (binary64) give the same contacts up to rounding, differing only on grazing pairs;
// bad spheres are reported once and never collided.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "afu_contract.hpp"
#include "batch/sane_ranges.hpp"
#include "cli/spheres_csv.hpp"
#include "collide/input_policy.hpp"
#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "support/random_world.hpp"
#include "support/test_seed.hpp"
#include "world/grid_broad_phase.hpp"
#include "world/ode_space_broad_phase.hpp"
#include "world/world_collider.hpp"

using namespace collide;
using namespace collide::world;

namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;
struct Contact {
  double px, py, pz, nx, ny, nz, depth;
  std::uint8_t flags;
  bool operator==(const Contact& o) const {
    return px == o.px && py == o.py && pz == o.pz && nx == o.nx && ny == o.ny && nz == o.nz && depth == o.depth &&
           flags == o.flags;
  }
};
using Contacts = std::map<Pair, Contact>;

Contacts asMap(const WorldContacts& w) {
  Contacts m;
  const auto& c = w.contacts;
  for (std::size_t k = 0; k < w.pairs.size(); ++k) {
    if (k > 0) {
      EXPECT_LT(std::make_pair(w.pairs.i[k - 1], w.pairs.j[k - 1]), std::make_pair(w.pairs.i[k], w.pairs.j[k]));
    }
    EXPECT_LT(w.pairs.i[k], w.pairs.j[k]);
    m[{w.pairs.i[k], w.pairs.j[k]}] = {c.px[k], c.py[k], c.pz[k], c.nx[k], c.ny[k], c.nz[k], c.depth[k], c.flags[k]};
  }
  return m;
}

Contacts worldContacts(BroadPhase& broad, CollisionBackend& narrow, SphereTable t, WorldContacts* keep = nullptr) {
  // An ODE space with the ode narrow phase: dCollide on the space's own geoms, as `collide spheres`.
  auto* space = dynamic_cast<OdeSpaceBroadPhase*>(&broad);
  std::vector<dGeomID> none;
  const OdeGeomBinding geoms(space ? dynamic_cast<OdeBackend*>(&narrow) : nullptr, space ? space->geoms() : none);
  WorldCollider wc(broad, narrow);
  WorldContacts w;
  WorldTiming time;
  wc.collide(t, w, time);
  if (keep) *keep = w;
  return asMap(w);
}

// The `collide pairs` path over all pairs of good spheres: what world mode must reproduce.
Contacts allPairs(CollisionBackend& b, const SphereTable& t) {
  PairList all;
  for (std::uint32_t i = 0; i < t.size(); ++i)
    for (std::uint32_t j = i + 1; j < t.size(); ++j)
      if (classifySphere(t, i) == PairInput::Ok && classifySphere(t, j) == PairInput::Ok) all.push(i, j);
  ContactSet c;
  collidePairs(b, t, all, c);
  Contacts m;
  for (std::size_t k = 0; k < all.size(); ++k)
    if (c.hit[k]) m[{all.i[k], all.j[k]}] = {c.px[k], c.py[k], c.pz[k], c.nx[k], c.ny[k], c.nz[k], c.depth[k], c.flags[k]};
  return m;
}

SphereTable cloud(std::uint64_t seed, bool mixed) {
  test::WorldShape s;
  s.spheres = 1500;
  s.extent = 7;
  if (mixed) {
    s.rMin = 0.02;
    s.rMax = 3;
    s.logRadii = true;
  }
  return test::randomWorld(seed, s);
}

}  // namespace

TEST(WorldCollider, TheGridWithTheSimdKernelFindsEveryContactOfAllPairsBitForBit) {
  const auto seed = test::testSeed(1201);
  for (bool mixed : {false, true}) {
    const auto t = cloud(seed, mixed);
    GridBroadPhase grid;
    SimdBackend simd;
    const auto want = allPairs(simd, t);
    EXPECT_GT(want.size(), 500u);
    EXPECT_TRUE(worldContacts(grid, simd, t) == want) << (mixed ? "mixed radii" : "uniform radii");
  }
}

TEST(WorldCollider, OdeHashAndSweepAndPruneSpacesGiveAllPairsContactsBitForBit) {
  const auto seed = test::testSeed(1202);
  for (bool mixed : {false, true}) {
    const auto t = cloud(seed, mixed);
    OdeBackend ode;
    const auto want = allPairs(ode, t);
    OdeSpaceBroadPhase hash(OdeSpaceKind::Hash), sap(OdeSpaceKind::SweepAndPrune);
    EXPECT_TRUE(worldContacts(hash, ode, t) == want) << "hash, " << (mixed ? "mixed radii" : "uniform radii");
    EXPECT_TRUE(worldContacts(sap, ode, t) == want) << "sap, " << (mixed ? "mixed radii" : "uniform radii");
  }
}

TEST(WorldCollider, SimdAndOdeGiveTheSameContactsButForGrazingPairs) {
  const auto seed = test::testSeed(1203);
  for (bool mixed : {false, true}) {
    const auto t = cloud(seed, mixed);
    GridBroadPhase grid;
    OdeSpaceBroadPhase sap(OdeSpaceKind::SweepAndPrune);
    SimdBackend simd;
    OdeBackend ode;
    const auto a = worldContacts(grid, simd, t), b = worldContacts(sap, ode, t);
    // A pair only one side calls a hit must graze: binary32 rounds d and r1 + r2 within a few
    // ulps, so |d - (r1 + r2)| (in binary64) is within a few binary32 ulps of r1 + r2.
    auto grazing = [&](const Pair& p) {
      const auto i = p.first, j = p.second;
      const double d = std::sqrt((t.x[i] - t.x[j]) * (t.x[i] - t.x[j]) + (t.y[i] - t.y[j]) * (t.y[i] - t.y[j]) +
                                 (t.z[i] - t.z[j]) * (t.z[i] - t.z[j]));
      return std::fabs(d - (t.r[i] + t.r[j])) <= 8 * 0x1p-24 * (t.r[i] + t.r[j] + d);
    };
    std::size_t onlyOne = 0, both = 0;
    for (const auto& [p, c] : a)
      if (!b.count(p)) { ++onlyOne; EXPECT_TRUE(grazing(p)) << "only simd: (" << p.first << ", " << p.second << ")"; }
    for (const auto& [p, c] : b) {
      const auto it = a.find(p);
      if (it == a.end()) { ++onlyOne; EXPECT_TRUE(grazing(p)) << "only ode: (" << p.first << ", " << p.second << ")"; continue; }
      ++both;
      // Values within a few binary32 ulps of the scene's scale (coordinates up to 7 m).
      const double pos = 8 * 0x1p-24 * 8, unit = 8 * 0x1p-24, depth = 8 * 0x1p-24 * (t.r[p.first] + t.r[p.second] + 8);
      const auto& s = it->second;
      EXPECT_NEAR(s.px, c.px, pos); EXPECT_NEAR(s.py, c.py, pos); EXPECT_NEAR(s.pz, c.pz, pos);
      EXPECT_NEAR(s.nx, c.nx, unit); EXPECT_NEAR(s.ny, c.ny, unit); EXPECT_NEAR(s.nz, c.nz, unit);
      EXPECT_NEAR(s.depth, c.depth, depth);
      EXPECT_EQ(s.flags, c.flags) << "(" << p.first << ", " << p.second << ")";
    }
    EXPECT_GT(both, 500u);
    EXPECT_LE(onlyOne, 2u) << "random binary32 worlds rarely graze";
  }
}

TEST(WorldCollider, AChainOfGrazingSpheresGivesOnlyNeighbourContactsOnEitherBackend) {
  // 0.1 is no binary32 value: spheres of radius 0.1f about two radii apart graze, and each
  // format rounds d and 2r its own way, so the two may keep different neighbours; nothing else.
  SphereTable t;
  for (int k = 0; k < 200; ++k) t.push(static_cast<float>(0.2 * k), 0, 0, static_cast<float>(0.1));
  GridBroadPhase grid;
  OdeSpaceBroadPhase hash(OdeSpaceKind::Hash);
  SimdBackend simd;
  OdeBackend ode;
  const auto a = worldContacts(grid, simd, t), b = worldContacts(hash, ode, t);
  for (const auto& [p, c] : a) EXPECT_EQ(p.second, p.first + 1) << "only neighbours can touch";
  for (const auto& [p, c] : b) EXPECT_EQ(p.second, p.first + 1) << "only neighbours can touch";
  EXPECT_TRUE(a == allPairs(simd, t));
  EXPECT_TRUE(b == allPairs(ode, t));
}

TEST(WorldCollider, BadSpheresAreReportedOnceAndNeverCollided) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  SphereTable t;
  t.push(0, 0, 0, 1);     // 0: touches 1 and the bad ones' places
  t.push(1.5, 0, 0, 1);   // 1
  t.push(nan, 0, 0, 1);   // 2: non-finite
  t.push(0, 0, 0, -1);    // 3: negative radius
  t.push(0.5, 0, 0, inf); // 4: non-finite
  t.push(2e6, 0, 0, 1);   // 5: beyond ODE's range
  t.push(0.2, 0, 0, 0);   // 6: zero radius
  SimdBackend simd;
  OdeBackend ode;
  GridBroadPhase grid;
  OdeSpaceBroadPhase hash(OdeSpaceKind::Hash);
  for (auto [broad, narrow] : {std::pair<BroadPhase*, CollisionBackend*>{&grid, &simd}, {&hash, &ode}}) {
    WorldContacts w;
    const auto c = worldContacts(*broad, *narrow, t, &w);
    ASSERT_EQ(c.size(), 1u) << broad->name();
    EXPECT_EQ(c.begin()->first, Pair(0, 1));
    EXPECT_EQ(w.badSpheres, (std::vector<std::uint32_t>{2, 3, 4, 5, 6}));
    const std::uint8_t nf = contract::REC_NONFINITE, range = contract::REC_HOST_RANGE;
    EXPECT_EQ(w.badFlags, (std::vector<std::uint8_t>{nf, range, nf, range, range})) << broad->name();

    std::ostringstream csv;
    cli::writeWorldContactsCsv(csv, w);
    const std::string zeros = narrow->format() == LinkFormat::Binary32 ? ",0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0"
                                                                        : ",0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0";
    const std::string rows = csv.str();
    EXPECT_EQ(rows.rfind("i,j,px,py,pz,nx,ny,nz,depth,flags\n0,1,", 0), 0u) << rows;
    EXPECT_NE(rows.find("\n2," + zeros + ",8\n3," + zeros + ",32\n4," + zeros + ",8\n5," + zeros + ",32\n6," + zeros +
                        ",32\n"),
              std::string::npos)
        << rows;
  }
}

TEST(WorldCollider, AnEmptyWorldAndOneSphereHaveNoContacts) {
  SimdBackend simd;
  OdeBackend ode;
  GridBroadPhase grid;
  OdeSpaceBroadPhase sap(OdeSpaceKind::SweepAndPrune);
  SphereTable one;
  one.push(1, 2, 3, 0.5);
  for (const auto& t : {SphereTable{}, one}) {
    EXPECT_TRUE(worldContacts(grid, simd, t).empty());
    EXPECT_TRUE(worldContacts(sap, ode, t).empty());
  }
}

TEST(WorldCollider, RepeatedRunsOnOneColliderGiveTheSameContacts) {
  const auto t = cloud(test::testSeed(1204), false);
  OdeSpaceBroadPhase hash(OdeSpaceKind::Hash);
  GridBroadPhase grid;
  OdeBackend ode;
  SimdBackend simd;
  ode.useGeoms(&hash.geoms());  // as `collide spheres --backend ode`
  WorldCollider a(hash, ode), b(grid, simd);
  WorldContacts w1, w2, w3, w4;
  WorldTiming time;
  SphereTable s = t;
  a.collide(s, w1, time);
  a.collide(s, w2, time);  // the space's geoms moved in place, not created again
  b.collide(s, w3, time);
  b.collide(s, w4, time);
  EXPECT_TRUE(asMap(w1) == asMap(w2));
  EXPECT_TRUE(asMap(w3) == asMap(w4));
  EXPECT_EQ(w1.candidates, w2.candidates);
  EXPECT_GT(time.broadNs, 0);
}

TEST(WorldCollider, AnOdeHashSpaceRefusesMoreSpheresThanItHoldsAndSweepAndPruneTakesThem) {
  // 131,072 spheres made ODE's hash space assert (its tested-pairs matrix passes the int
  // range); the refusal comes before any geom is made and says what to use instead.
  SphereTable t;
  const auto n = static_cast<std::uint32_t>(limits::kMaxHashSpaceSpheres + 1);
  std::vector<std::uint32_t> members(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    t.push(k % 512, (k / 512) % 512, k / (512 * 512), 0.1);
    members[k] = k;
  }
  OdeSpaceBroadPhase hash(OdeSpaceKind::Hash), sap(OdeSpaceKind::SweepAndPrune);
  try {
    hash.prepare(t, members);
    ADD_FAILURE() << "no refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("131072 spheres, more than ODE's hash space holds (131071", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("use --space sap"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(hash.geoms().empty());
  sap.prepare(t, members);
  EXPECT_EQ(sap.geoms().size(), t.size());
}
