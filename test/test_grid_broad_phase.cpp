// The grid broad phase (world/grid_broad_phase.hpp) against all pairs: on random worlds and
// the hard cases it yields exactly the pairs its rule defines (checked pair by pair, no
// duplicates), and those include every pair the simd (binary32) or ode (binary64) narrow
// phase calls a hit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "support/random_world.hpp"
#include "support/test_seed.hpp"
#include "world/grid_broad_phase.hpp"

using namespace collide;
using world::GridBroadPhase;

namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

std::vector<std::uint32_t> everySphere(const SphereTable& t) {
  std::vector<std::uint32_t> m(t.size());
  for (std::uint32_t k = 0; k < t.size(); ++k) m[k] = k;
  return m;
}

// The rule, written out over all pairs: large or in neighbouring cells, and grown boxes overlap.
std::vector<Pair> rulePairs(const SphereTable& t, int k) {
  std::vector<Pair> out;
  for (std::uint32_t i = 0; i < t.size(); ++i)
    for (std::uint32_t j = i + 1; j < t.size(); ++j) {
      bool neighbours = true;
      for (const auto* c : {&t.x, &t.y, &t.z})
        neighbours = neighbours &&
                     std::abs(std::int64_t{GridBroadPhase::cellOf((*c)[i], k)} - GridBroadPhase::cellOf((*c)[j], k)) <= 1;
      const bool large = GridBroadPhase::isLarge(t.r[i], k) || GridBroadPhase::isLarge(t.r[j], k);
      if ((large || neighbours) &&
          GridBroadPhase::boxesOverlap(t.x[i] - t.x[j], t.y[i] - t.y[j], t.z[i] - t.z[j],
                                       GridBroadPhase::reachOf(t.r[i]) + GridBroadPhase::reachOf(t.r[j])))
        out.emplace_back(i, j);
    }
  return out;
}

// Pairs each narrow phase calls a hit, over all pairs.
std::set<Pair> hitsOf(CollisionBackend& b, const SphereTable& t) {
  PairList all;
  for (std::uint32_t i = 0; i < t.size(); ++i)
    for (std::uint32_t j = i + 1; j < t.size(); ++j) all.push(i, j);
  ContactSet c;
  b.collide(t, all, c);
  std::set<Pair> hits;
  for (std::size_t k = 0; k < all.size(); ++k)
    if (c.hit[k]) hits.emplace(all.i[k], all.j[k]);
  return hits;
}

// The grid's pairs: exactly the rule's, each once as i < j, and a superset of every hit.
// Returns how many hits there were.
std::size_t checkWorld(const SphereTable& t, const std::string& what) {
  GridBroadPhase grid;
  PairList got;
  grid.findPairs(t, everySphere(t), got);
  const auto& shape = grid.lastShape();
  std::vector<Pair> pairs;
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_LT(got.i[k], got.j[k]) << what;
    pairs.emplace_back(got.i[k], got.j[k]);
  }
  std::sort(pairs.begin(), pairs.end());
  EXPECT_EQ(std::adjacent_find(pairs.begin(), pairs.end()), pairs.end()) << what << ": a pair came out twice";
  const auto want = rulePairs(t, shape.cellExp);
  EXPECT_EQ(pairs.size(), want.size()) << what;
  EXPECT_TRUE(pairs == want) << what << ": the grid's pairs differ from its rule's";
  EXPECT_LE(shape.large, GridBroadPhase::kMaxLarge) << what;

  const std::set<Pair> have(pairs.begin(), pairs.end());
  SimdBackend simd;
  OdeBackend ode;
  std::size_t hits = 0;
  for (CollisionBackend* b : {static_cast<CollisionBackend*>(&simd), static_cast<CollisionBackend*>(&ode)}) {
    const auto h = hitsOf(*b, t);
    hits = std::max(hits, h.size());
    for (const auto& p : h)
      EXPECT_TRUE(have.count(p)) << what << ": " << b->name() << " hit (" << p.first << ", " << p.second
                                 << ") is no candidate";
  }
  return hits;
}

SphereTable table(std::initializer_list<std::array<double, 4>> spheres) {
  SphereTable t;
  for (const auto& s : spheres) t.push(s[0], s[1], s[2], s[3]);
  return t;
}

}  // namespace

TEST(GridBroadPhase, RandomWorldsGiveExactlyTheRulesPairsAndEveryHit) {
  const auto seed = test::testSeed(1101);
  std::size_t hits = 0;
  for (int w = 0; w < 6; ++w) {
    test::WorldShape shape;
    shape.spheres = 400 + 100 * w;
    shape.extent = 4 + w;
    hits += checkWorld(test::randomWorld(seed + w, shape), "uniform world " + std::to_string(w));
  }
  EXPECT_GT(hits, 1000u) << "the worlds have contacts to find";
}

TEST(GridBroadPhase, MixedSizesOneToAThousandGiveEveryHit) {
  const auto seed = test::testSeed(1102);
  test::WorldShape shape;
  shape.spheres = 600;
  shape.extent = 20;
  shape.rMin = 0.01;
  shape.rMax = 10;
  shape.logRadii = true;
  EXPECT_GT(checkWorld(test::randomWorld(seed, shape), "log-uniform radii 0.01..10"), 100u);
}

TEST(GridBroadPhase, AHugeSphereSpanningManyCellsMeetsEverySphereItTouches) {
  auto t = test::randomWorld(test::testSeed(1103), {500, 8, 0.1, 0.2, false});
  t.push(0.5, -0.25, 0, 5);  // 50 cells across
  GridBroadPhase grid;
  PairList p;
  grid.findPairs(t, everySphere(t), p);
  EXPECT_EQ(grid.lastShape().large, 1u);
  EXPECT_GT(checkWorld(t, "one huge sphere"), 50u);
}

TEST(GridBroadPhase, MoreThanSixteenLargeSpheresMakeTheCellsLarger) {
  auto t = test::randomWorld(test::testSeed(1104), {300, 6, 0.1, 0.2, false});
  for (int k = 0; k < 40; ++k) t.push(k % 7 - 3.0, k % 5 - 2.0, k % 3 - 1.0, 0.5 + 0.05 * k);  // 40 distinct large radii
  const auto shape = GridBroadPhase::chooseShape(t, everySphere(t));
  EXPECT_LE(shape.large, GridBroadPhase::kMaxLarge);
  // k is the least exponent that does it: one less would leave more than 16 large.
  std::size_t largeBelow = 0;
  for (double r : t.r) largeBelow += GridBroadPhase::isLarge(r, shape.cellExp - 1);
  EXPECT_GT(largeBelow, GridBroadPhase::kMaxLarge);
  EXPECT_LE(2.5 * shape.smallRadiusMax, std::ldexp(1.0, shape.cellExp));
  checkWorld(t, "40 large spheres");
}

TEST(GridBroadPhase, AllSpheresAtOnePointAreAllPairs) {
  SphereTable t;
  for (int k = 0; k < 60; ++k) t.push(-1.5, 2.25, 0, 0.5);
  EXPECT_EQ(checkWorld(t, "all at one point"), 60u * 59u / 2u);
}

TEST(GridBroadPhase, SpheresOnCellBoundariesAndNegativeCoordinatesAreFound) {
  // r = 0.4: cells 1 m wide (2.5 r = 1 exactly). Centres on the boundaries -2, -1, 0, 1 and
  // just off them, in every axis, touching exactly and overlapping.
  SphereTable t;
  for (double x : {-2.0, -1.0, -0.2, 0.0, 0.6, 1.0, 1.8})
    for (double y : {-1.0, 0.0, 0.8})
      for (double z : {-1.0, -0.2, 0.0})
        t.push(x, y, z, 0.4);
  const auto shape = GridBroadPhase::chooseShape(t, everySphere(t));
  EXPECT_EQ(shape.cellExp, 0);
  EXPECT_EQ(shape.large, 0u);
  EXPECT_GT(checkWorld(t, "cell boundaries"), 50u);
  EXPECT_EQ(GridBroadPhase::cellOf(-1.0, 0), -1);
  EXPECT_EQ(GridBroadPhase::cellOf(std::nextafter(-1.0, 0.0), 0), -1);
  EXPECT_EQ(GridBroadPhase::cellOf(std::nextafter(-1.0, -2.0), 0), -2);
  EXPECT_EQ(GridBroadPhase::cellOf(1.0, 0), 1);
  EXPECT_EQ(GridBroadPhase::cellOf(std::nextafter(1.0, 0.0), 0), 0);
  EXPECT_EQ(GridBroadPhase::cellOf(-0.0, 0), 0);
}

TEST(GridBroadPhase, ATinyNegativeCoordinateIsInCellMinusOne) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(GridBroadPhase::cellOf(-tiny, 5), -1) << "c / 2^k underflows to -0, yet c < 0";
  EXPECT_EQ(GridBroadPhase::cellOf(tiny, 5), 0);
  checkWorld(table({{-tiny, 0, 0, 1}, {31.9, 0, 0, 1}, {-31.9, 0, 0, 1}, {-2, 0, 0, 1}}), "tiny coordinates");
}

TEST(GridBroadPhase, AnEmptyWorldAndOneSphereGiveNoPairs) {
  GridBroadPhase grid;
  PairList p;
  grid.findPairs(SphereTable{}, {}, p);
  EXPECT_EQ(p.size(), 0u);
  const auto one = table({{1, 2, 3, 0.5}});
  grid.findPairs(one, everySphere(one), p);
  EXPECT_EQ(p.size(), 0u);
  checkWorld(table({{0, 0, 0, 1}, {1.5, 0, 0, 1}}), "two spheres");
}

TEST(GridBroadPhase, OnlyTheMembersArePaired) {
  const auto t = table({{0, 0, 0, 1}, {0.5, 0, 0, 1}, {1, 0, 0, 1}, {1.5, 0, 0, 1}});
  GridBroadPhase grid;
  PairList p;
  grid.findPairs(t, {0, 2, 3}, p);
  for (std::size_t k = 0; k < p.size(); ++k) {
    EXPECT_NE(p.i[k], 1u);
    EXPECT_NE(p.j[k], 1u);
  }
  EXPECT_EQ(p.size(), 3u);
}

TEST(GridBroadPhase, TinyRadiiUseTheLeastCell) {
  const auto t = table({{0, 0, 0, 1e-9}, {1e-9, 0, 0, 1e-9}, {1e-3, 0, 0, 1e-9}});
  const auto shape = GridBroadPhase::chooseShape(t, everySphere(t));
  EXPECT_EQ(shape.cellExp, GridBroadPhase::kMinCellExp);
  checkWorld(t, "tiny radii");
}
