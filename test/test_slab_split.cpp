// world/slab_split: cutting a world larger than an AFU run into slabs along x, or into boxes
// along x and y where slabs cannot hold it. Every touching pair must be kept by exactly one
// run, with both its spheres in that run's table, and no run may exceed its cap.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/test_seed.hpp"
#include "world/slab_split.hpp"

using namespace collide::world;

namespace {

struct World {
  std::vector<double> x, y, z, r;
  void push(double a, double b, double c, double rad) { x.push_back(a); y.push_back(b); z.push_back(c); r.push_back(rad); }
};

// For every touching pair (i < j), the runs that keep it; and each run's size.
void expectEveryContactOnce(const World& w, const std::vector<Slab>& runs, std::size_t cap, const std::string& what) {
  const std::size_t n = w.x.size();
  std::vector<std::vector<std::size_t>> at(n);  // sphere -> (run, position) flattened as run * n + position
  for (std::size_t b = 0; b < runs.size(); ++b) {
    EXPECT_LE(runs[b].spheres.size(), cap) << what << ": run " << b;
    for (std::size_t k = 1; k < runs[b].spheres.size(); ++k) ASSERT_LT(runs[b].spheres[k - 1], runs[b].spheres[k]) << what;
    for (std::size_t k = 0; k < runs[b].spheres.size(); ++k) at[runs[b].spheres[k]].push_back(b * n + k);
  }
  std::size_t contacts = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (std::hypot(w.x[i] - w.x[j], w.y[i] - w.y[j], w.z[i] - w.z[j]) > w.r[i] + w.r[j]) continue;
      ++contacts;
      int kept = 0;
      for (auto a : at[i])
        for (auto b : at[j])
          if (a / n == b / n && keepsPair(runs[a / n], a % n, b % n)) ++kept;
      EXPECT_EQ(kept, 1) << what << ": pair (" << i << ", " << j << ")";
    }
  EXPECT_GT(contacts, 0u) << what;
}

}  // namespace

TEST(SlabSplit, CutsARandomWorldAlongXAndKeepsEveryContactOnce) {
  std::mt19937_64 rng(collide::test::testSeed(2611));
  std::uniform_real_distribution<double> pos(-6, 6), rad(0.1, 0.9);
  World w;
  for (int k = 0; k < 900; ++k) w.push(pos(rng), pos(rng), pos(rng), rad(rng));
  const auto runs = splitIntoBoxes(w.x, w.y, w.r, 200);
  EXPECT_GE(runs.size(), 5u);
  for (const auto& s : runs)
    for (auto o : s.owned) EXPECT_TRUE(o == 0 || o == kOwnedBoth);  // slabs: owned or a ghost
  expectEveryContactOnce(w, runs, 200, "random world, slabs");
}

TEST(SlabSplit, CutsAWallTooThickForSlabsIntoBoxesAndKeepsEveryContactOnce) {
  // 10 x 40 x 4 touching spheres (0.9 apart, radius 0.5): a sphere and those within reach of
  // it along x are two layers (320), so runs of 150 need boxes along x and y: slabs of at most
  // 600 along x, each cut into strips along y.
  World w;
  for (int a = 0; a < 10; ++a)
    for (int b = 0; b < 40; ++b)
      for (int c = 0; c < 4; ++c) w.push(0.9 * a, 0.9 * b, 0.9 * c, 0.5);
  EXPECT_THROW(splitIntoSlabs(w.x, w.r, 150), std::runtime_error);
  const auto runs = splitIntoBoxes(w.x, w.y, w.r, 150);
  EXPECT_GE(runs.size(), 11u);  // 1,600 spheres, at most 150 a run
  bool ghostX = false, ghostY = false;  // owned along one axis only: both kinds occur
  for (const auto& s : runs)
    for (auto o : s.owned) { ghostX |= o == kOwnedY; ghostY |= o == kOwnedX; }
  EXPECT_TRUE(ghostX && ghostY);
  expectEveryContactOnce(w, runs, 150, "wall, boxes");
}

TEST(SlabSplit, RefusesAWorldNoBoxHoldsAndNamesTheSphere) {
  // 300 spheres far apart (along x and y), then 150 in one place: the refusal names
  // the dense group's first sphere along y by its index in the world (300), not in its slab.
  World w;
  for (int k = 0; k < 300; ++k) w.push(-1000.0 - 10 * k, 10.0 * k, 0, 0.5);
  for (int k = 0; k < 150; ++k) w.push(1.0, 0.01 * k, 0, 0.5);
  try {
    splitIntoBoxes(w.x, w.y, w.r, 100);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("sphere 300 and the"), std::string::npos) << m;
    EXPECT_NE(m.find("touch it along y"), std::string::npos) << m;
    EXPECT_NE(m.find("nor into boxes along x and y"), std::string::npos) << m;
  }
}

TEST(SlabSplit, ChoosesTheCutWithTheFewestSpheresColumnsOverSlabsInACubeAndKeepsEveryContactOnce) {
  // 6,000 spheres in a cube, runs of 400: slabs along x fit, but each carries a ghost layer
  // about half its own thickness; columns along z cut along x and y carry two thinner ones.
  std::mt19937_64 rng(collide::test::testSeed(2614));
  std::uniform_real_distribution<double> pos(0, 22), rad(0.3, 0.6);
  World w;
  for (int k = 0; k < 6000; ++k) w.push(pos(rng), pos(rng), pos(rng), rad(rng));
  const std::size_t cap = 400;
  const auto slabs = splitIntoSlabs(w.x, w.r, cap);
  const auto runs = splitIntoRuns(w.x, w.y, w.r, cap);
  EXPECT_LT(sphereCount(runs), sphereCount(slabs)) << runs.size() << " runs against " << slabs.size() << " slabs";
  // never worse than the old rule by the measure it minimizes (a run counts for cap / 16 spheres)
  const auto old = splitIntoBoxes(w.x, w.y, w.r, cap);
  EXPECT_LE(cutCost(runs, cap), cutCost(old, cap));
  bool ghostX = false, ghostY = false;
  for (const auto& s : runs)
    for (auto o : s.owned) { ghostX |= o == kOwnedY; ghostY |= o == kOwnedX; }
  EXPECT_TRUE(ghostX && ghostY) << "not boxes";
  for (const auto& s : runs) EXPECT_LE(runs.front().spheres.size(), s.spheres.size()) << "the smallest run is not first";
  expectEveryContactOnce(w, runs, cap, "cube, fewest spheres");
}
