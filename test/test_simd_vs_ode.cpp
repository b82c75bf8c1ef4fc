// simd (binary32) against ODE's own dCollide (binary64) on random pairs: the same answer
// up to float rounding. Pairs within a few float ulps of grazing may disagree on hit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>

#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "support/test_seed.hpp"

using namespace collide;

namespace {
// 20,000 random pairs of two spheres each (pair k: spheres 2k, 2k + 1), then an exactly
// coincident pair (20000) and an exactly grazing one (20001), both representable in float.
void randomPairs(std::uint64_t seed, SphereTable& t, PairList& p) {
  std::mt19937_64 rng(test::testSeed(seed));
  std::uniform_real_distribution<double> pos(-1.0, 1.0), rad(0.05, 0.6);
  for (int k = 0; k < 20000; ++k) {
    t.push(pos(rng), pos(rng), pos(rng), rad(rng));
    t.push(pos(rng), pos(rng), pos(rng), rad(rng));
    p.push(2 * k, 2 * k + 1);
  }
  t.push(0.25, 0.5, 0.75, 0.5); t.push(0.25, 0.5, 0.75, 0.25); p.push(40000, 40001);
  t.push(3, 4, 0, 2); t.push(0, 0, 0, 3); p.push(40002, 40003);
}
}  // namespace

TEST(SimdVsOde, AgreeWithinFloatTolerance) {
  SphereTable t;
  PairList p;
  randomPairs(51, t, p);

  ContactSet a, b;
  OdeBackend().collide(t, p, a);
  SimdBackend().collide(t, p, b);
  ASSERT_EQ(a.size(), b.size());
  std::size_t hits = 0, nearGrazing = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto i = p.i[k], j = p.j[k];
    const double d = std::hypot(t.x[i] - t.x[j], t.y[i] - t.y[j], t.z[i] - t.z[j]);
    const double gap = d - (t.r[i] + t.r[j]);
    if (std::fabs(gap) < 1e-6) {  // float cannot decide these the way double does
      ++nearGrazing;
      continue;
    }
    ASSERT_EQ(a.hit[k], b.hit[k]) << "pair " << k << " gap " << gap;
    if (!a.hit[k]) continue;
    ++hits;
    // binary32 rounds each input by u |v| and each step by u: the centres' difference is off by
    // a few u M (M the largest coordinate), so the normal by a few u (M / d + 1), the position
    // by that times the radius plus u M, the depth by a few u (M + radii). A fixed tolerance
    // fails for close centres (seed 2232738508: 2.03e-6 on a normal at d = 0.28).
    const double u = std::ldexp(1.0, -24), c = 8;
    const double m = std::max({std::fabs(t.x[i]), std::fabs(t.y[i]), std::fabs(t.z[i]), std::fabs(t.x[j]),
                               std::fabs(t.y[j]), std::fabs(t.z[j]), 1.0});
    const double rr = t.r[i] + t.r[j];
    const double tolN = c * u * (m / d + 1), tolP = c * u * m + rr * tolN, tolD = c * u * (m + rr);
    EXPECT_NEAR(a.nx[k], b.nx[k], tolN) << k << " d " << d;
    EXPECT_NEAR(a.ny[k], b.ny[k], tolN) << k << " d " << d;
    EXPECT_NEAR(a.nz[k], b.nz[k], tolN) << k << " d " << d;
    EXPECT_NEAR(a.px[k], b.px[k], tolP) << k << " d " << d;
    EXPECT_NEAR(a.py[k], b.py[k], tolP) << k << " d " << d;
    EXPECT_NEAR(a.pz[k], b.pz[k], tolP) << k << " d " << d;
    EXPECT_NEAR(a.depth[k], b.depth[k], tolD) << k << " d " << d;
  }
  EXPECT_GT(hits, 2000u);
  EXPECT_LT(nearGrazing, 10u);
  // The two exact cases agree exactly.
  const std::size_t c = p.size() - 2, g = p.size() - 1;
  EXPECT_TRUE(a.hit[c] && b.hit[c]);
  EXPECT_EQ(a.nx[c], 1.0);
  EXPECT_EQ(b.nx[c], 1.0);
  EXPECT_EQ(a.depth[c], 0.75);
  EXPECT_EQ(b.depth[c], 0.75);
  EXPECT_TRUE(a.hit[g] && b.hit[g]);
  EXPECT_EQ(a.depth[g], 0.0);
  EXPECT_EQ(b.depth[g], 0.0);
}

TEST(SimdVsOde, Simd64IsOdesOwnArithmeticBitForBit) {
  // The binary64 kernel does ODE's dCollideSpheres operations in ODE's order, so on every pair,
  // grazing ones included, it gives ODE's contacts to the bit.
  SphereTable t;
  PairList p;
  randomPairs(53, t, p);
  t.push(3, 4, 0, 2 - 0x1.0p-50); t.push(0, 0, 0, 3); p.push(40004, 40005);  // an ulp apart
  ContactSet a, b;
  OdeBackend().collide(t, p, a);
  SimdBackend simd64(LinkFormat::Binary64);
  EXPECT_EQ(simd64.name(), "simd64");
  simd64.collide(t, p, b);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(b.format, LinkFormat::Binary64);
  auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  std::size_t hits = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    ASSERT_EQ(a.hit[k], b.hit[k]) << "pair " << k;
    hits += a.hit[k];
    const double* ca[7] = {&a.px[k], &a.py[k], &a.pz[k], &a.nx[k], &a.ny[k], &a.nz[k], &a.depth[k]};
    const double* cb[7] = {&b.px[k], &b.py[k], &b.pz[k], &b.nx[k], &b.ny[k], &b.nz[k], &b.depth[k]};
    for (int c = 0; c < 7; ++c) ASSERT_TRUE(same(*ca[c], *cb[c])) << "pair " << k << " field " << c;
  }
  EXPECT_GT(hits, 1000u);
  EXPECT_TRUE(b.hit[20001] && !b.hit[20002]);
  EXPECT_THROW(SimdBackend(LinkFormat::Binary16), std::invalid_argument);
}
