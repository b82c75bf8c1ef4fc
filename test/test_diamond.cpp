// The paper's diamond generator: sphere count and positions per docs/host.md, "Diamond geometry".
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "scene/diamond.hpp"

using namespace collide::scene;

TEST(Diamond, SphereCountFollowsTheFormula) {
  const long long expected[] = {1, 6, 19, 44, 85, 146, 231, 344, 489, 670};  // hMax(2hMax^2+1)/3
  for (int h = 1; h <= 10; ++h) {
    EXPECT_EQ(diamondSphereCount(h), expected[h - 1]) << "hMax " << h;
    EXPECT_EQ(static_cast<long long>(diamondCentres({h, 0.0, 0.1}).size()), expected[h - 1]) << "hMax " << h;
  }
}

TEST(Diamond, PositionsFollowTheFormulas) {
  for (double dSph : {0.0, 0.05}) {
    const double r = 0.1, hip = std::sqrt(0.08), db = hip - 2 * r + dSph, a = db / 2 + r;
    const int h = 3;
    const auto c = diamondCentres({h, dSph, r});
    // Layers of 1, 4, 9, 4, 1 spheres at z = step*db + 2r + 4.
    std::map<double, int> perLayer;
    for (const auto& p : c) perLayer[p[2]]++;
    ASSERT_EQ(perLayer.size(), 5u);
    const int sizes[] = {1, 4, 9, 4, 1};  // spheres per layer (n x n)
    int step = 0;
    for (const auto& [z, n] : perLayer) {
      EXPECT_NEAR(z, step * db + 2 * r + 4, 1e-12);
      EXPECT_EQ(n, sizes[step]);
      ++step;
    }
    // Layer 0 is the apex on the axis; layer 1 is 2x2 rotated 45 degrees: (+-a, 0), (0, +-a).
    EXPECT_NEAR(c[0][0], 0.0, 1e-15);
    EXPECT_NEAR(c[0][1], 0.0, 1e-15);
    std::multiset<std::pair<long, long>> l1;
    for (int k = 1; k <= 4; ++k) l1.insert({std::lround(c[k][0] / a), std::lround(c[k][1] / a)});
    EXPECT_EQ(l1, (std::multiset<std::pair<long, long>>{{-1, 0}, {0, -1}, {0, 1}, {1, 0}}));
    for (int k = 1; k <= 4; ++k) EXPECT_NEAR(std::hypot(c[k][0], c[k][1]), a, 1e-12);
    // In-layer lattice neighbours are a*sqrt(2) apart: exactly touching (2r) at dSph = 0.
    double nearest = 1e9;
    for (int i = 1; i <= 4; ++i)
      for (int j = i + 1; j <= 4; ++j) nearest = std::min(nearest, std::hypot(c[i][0] - c[j][0], c[i][1] - c[j][1]));
    EXPECT_NEAR(nearest, a * std::sqrt(2.0), 1e-12);
    if (dSph == 0) {
      EXPECT_NEAR(nearest, 2 * r, 1e-12);
    }
  }
}

TEST(Diamond, CentreIsTheCentroid) {
  for (int h : {1, 4, 10}) {
    const auto c = diamondCentres({h, 0.0, 0.1});
    double s[3] = {0, 0, 0};
    for (const auto& p : c)
      for (int k = 0; k < 3; ++k) s[k] += p[k];
    const auto m = diamondCentre({h, 0.0, 0.1});
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(s[k] / c.size(), m[k], 1e-9) << "hMax " << h;
  }
}

TEST(Diamond, TouchingAndOverlappingPairsAtHMax10) {
  // Our reading of the geometry gives 3909 pairs with d <= 2r (+1e-12) at step 0:
  // a regression guard for the generator (the paper's 4,812 is for its pushed run).
  const auto c = diamondCentres({10, 0.0, 0.1});
  int n = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = i + 1; j < c.size(); ++j)
      n += std::hypot(c[i][0] - c[j][0], c[i][1] - c[j][1], c[i][2] - c[j][2]) <= 0.2 + 1e-12;
  EXPECT_EQ(n, 3909);
}
