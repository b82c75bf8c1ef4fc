// The simd kernels against a plain scalar dCollideSpheres, bit for bit, in binary32 and
// binary64, on random pairs and on the hard cases of docs/scpu.md ("Hard cases").
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

#include "collide/simd_kernel.hpp"
#include "support/test_seed.hpp"

using namespace collide;

namespace {

template <typename T> struct PT { T x1, y1, z1, r1, x2, y2, z2, r2; };
template <typename T> struct CT { bool hit; T px, py, pz, nx, ny, nz, depth; };
using P = PT<float>;
using C = CT<float>;

// Straight transcription of ODE's dCollideSpheres in T, with branches (this file is compiled
// with -ffp-contract=off like the rest of the project).
template <typename T>
CT<T> reference(const PT<T>& p) {
  CT<T> c{false, 0, 0, 0, 0, 0, 0, 0};
  const T dx = p.x1 - p.x2, dy = p.y1 - p.y2, dz = p.z1 - p.z2;
  const T d = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (d > p.r1 + p.r2) return c;
  c.hit = true;
  if (d <= 0) {
    c.px = p.x1; c.py = p.y1; c.pz = p.z1;
    c.nx = 1; c.ny = 0; c.nz = 0;
    c.depth = p.r1 + p.r2;
  } else {
    const T d1 = T(1) / d;
    c.nx = (p.x1 - p.x2) * d1; c.ny = (p.y1 - p.y2) * d1; c.nz = (p.z1 - p.z2) * d1;
    const T k = T(0.5) * (p.r2 - p.r1 - d);
    c.px = p.x1 + c.nx * k; c.py = p.y1 + c.ny * k; c.pz = p.z1 + c.nz * k;
    c.depth = p.r1 + p.r2 - d;
  }
  return c;
}

template <typename T>
std::vector<CT<T>> kernel(const std::vector<PT<T>>& ps) {
  const std::size_t n = ps.size();
  std::vector<T> in[8], out[7];
  for (auto& v : in) v.resize(n);
  for (auto& v : out) v.resize(n);
  std::vector<std::uint8_t> hit(n);
  for (std::size_t k = 0; k < n; ++k) {
    const T v[8] = {ps[k].x1, ps[k].y1, ps[k].z1, ps[k].r1, ps[k].x2, ps[k].y2, ps[k].z2, ps[k].r2};
    for (int c = 0; c < 8; ++c) in[c][k] = v[c];
  }
  if constexpr (std::is_same_v<T, float>)
    collideSpheresF32(n, {in[0].data(), in[1].data(), in[2].data(), in[3].data(), in[4].data(), in[5].data(), in[6].data(), in[7].data()},
                      {out[0].data(), out[1].data(), out[2].data(), out[3].data(), out[4].data(), out[5].data(), out[6].data(), hit.data()});
  else
    collideSpheresF64(n, {in[0].data(), in[1].data(), in[2].data(), in[3].data(), in[4].data(), in[5].data(), in[6].data(), in[7].data()},
                      {out[0].data(), out[1].data(), out[2].data(), out[3].data(), out[4].data(), out[5].data(), out[6].data(), hit.data()});
  std::vector<CT<T>> r(n);
  for (std::size_t k = 0; k < n; ++k)
    r[k] = {hit[k] != 0, out[0][k], out[1][k], out[2][k], out[3][k], out[4][k], out[5][k], out[6][k]};
  return r;
}

std::uint32_t bits(float f) { std::uint32_t u; std::memcpy(&u, &f, 4); return u; }
std::uint64_t bits(double f) { std::uint64_t u; std::memcpy(&u, &f, 8); return u; }

// anyNaN: where the reference is a NaN, any NaN will do (the payload is the hardware's).
template <typename T>
void expectBitEqual(const std::vector<PT<T>>& ps, bool anyNaN = false) {
  const auto got = kernel(ps);
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const CT<T> want = reference(ps[k]);
    ASSERT_EQ(got[k].hit, want.hit) << "pair " << k;
    if (!want.hit) continue;
    const T g[7] = {got[k].px, got[k].py, got[k].pz, got[k].nx, got[k].ny, got[k].nz, got[k].depth};
    const T w[7] = {want.px, want.py, want.pz, want.nx, want.ny, want.nz, want.depth};
    for (int c = 0; c < 7; ++c) {
      if (anyNaN && std::isnan(w[c])) ASSERT_TRUE(std::isnan(g[c])) << "pair " << k << " component " << c;
      else ASSERT_EQ(bits(g[c]), bits(w[c])) << "pair " << k << " component " << c << ": " << g[c] << " vs " << w[c];
    }
  }
}

const float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kDen = std::numeric_limits<float>::denorm_min();

}  // namespace

TEST(SimdExact, RandomPairsBitForBit) {
  std::mt19937_64 rng(test::testSeed(41));
  std::uniform_real_distribution<float> pos(-2.0f, 2.0f), rad(0.0f, 1.5f);
  std::vector<P> ps;
  for (int k = 0; k < 100003; ++k)  // odd count: the vector loop's scalar tail runs too
    ps.push_back({pos(rng), pos(rng), pos(rng), rad(rng), pos(rng), pos(rng), pos(rng), rad(rng)});
  expectBitEqual(ps);
  // Random bit patterns: every exponent, subnormals, infinities, NaNs.
  std::vector<P> wild;
  auto any = [&] { std::uint32_t u = static_cast<std::uint32_t>(rng()); float f; std::memcpy(&f, &u, 4); return f; };
  for (int k = 0; k < 50001; ++k) wild.push_back({any(), any(), any(), any(), any(), any(), any(), any()});
  expectBitEqual(wild, /*anyNaN=*/true);
}

TEST(SimdExact, HardCases) {
  const float below = 2.0f - 0x1.0p-21f, above = 2.0f + 0x1.0p-21f;  // r1 + 3 = 5 -+ 1 ulp of 5
  const std::vector<P> ps = {
      {0, 0, 0, 1, 0, 0, 0, 2},                 // coincident centres
      {-0.0f, 0, 0, 1, 0.0f, -0.0f, 0, 1},      // +0 vs -0: still coincident
      {3, 4, 0, 2, 0, 0, 0, 3},                 // exact grazing: contact, depth 0
      {3, 4, 0, below, 0, 0, 0, 3},             // one ulp apart: no contact
      {3, 4, 0, above, 0, 0, 0, 3},             // one ulp overlap: depth 1 ulp of 5
      {1, 1, 1, 0, 1, 1, 1, 0},                 // zero radii, coincident: contact depth 0
      {1, 1, 1, 0, 1 + 0x1.0p-23f, 1, 1, 0},    // zero radii one ulp apart: no contact
      {0, 0, 0, 1, kDen, 0, 0, 1},              // separation whose square underflows to 0
      {3e19f, 0, 0, 1, -3e19f, 0, 0, 1},        // d^2 overflows: d = inf, no contact
      {1e30f, 0, 0, 1e30f, -1e30f, 0, 0, 1e30f},// huge radii near grazing
      {0, 0, 0, 1e-30f, 0, 0, 1e-31f, 1e20f},   // huge radius ratio
      {kNaN, 0, 0, 1, 0, 0, 0, 1},              // NaN: ODE's "not >" makes it a contact
      {0, 0, 0, kInf, 5, 0, 0, 1},              // infinite radius
      {1e7f, 1e7f, 1e7f, 0.5f, 1e7f + 1, 1e7f, 1e7f, 0.5f},  // large coordinates, small gap
  };
  expectBitEqual(ps);
  const auto got = kernel(ps);
  EXPECT_TRUE(got[0].hit);
  EXPECT_EQ(got[0].nx, 1.0f);
  EXPECT_EQ(got[0].depth, 3.0f);
  EXPECT_TRUE(got[1].hit);
  EXPECT_TRUE(got[2].hit);
  EXPECT_EQ(bits(got[2].depth), 0u);     // +0
  EXPECT_EQ(got[2].nx, 0.6f);
  EXPECT_EQ(got[2].ny, 0.8f);
  EXPECT_FALSE(got[3].hit);
  EXPECT_TRUE(got[4].hit);
  EXPECT_EQ(got[4].depth, 0x1.0p-21f);
  EXPECT_TRUE(got[5].hit);
  EXPECT_FALSE(got[6].hit);
  EXPECT_TRUE(got[7].hit);               // d^2 = 0 after underflow: the coincident path
  EXPECT_EQ(got[7].nx, 1.0f);
  EXPECT_FALSE(got[8].hit);
  EXPECT_TRUE(got[11].hit);
  EXPECT_TRUE(std::isnan(got[11].depth));
  EXPECT_TRUE(got[13].hit);
}

TEST(SimdExact, Binary64RandomPairsAndHardCasesBitForBit) {
  std::mt19937_64 rng(test::testSeed(43));
  std::uniform_real_distribution<double> pos(-2.0, 2.0), rad(0.0, 1.5);
  std::vector<PT<double>> ps;
  for (int k = 0; k < 100003; ++k)  // odd count: the vector loop's scalar tail runs too
    ps.push_back({pos(rng), pos(rng), pos(rng), rad(rng), pos(rng), pos(rng), pos(rng), rad(rng)});
  expectBitEqual(ps);
  std::vector<PT<double>> wild;
  auto any = [&] { const std::uint64_t u = rng(); double f; std::memcpy(&f, &u, 8); return f; };
  for (int k = 0; k < 50001; ++k) wild.push_back({any(), any(), any(), any(), any(), any(), any(), any()});
  expectBitEqual(wild, /*anyNaN=*/true);
  const double den = std::numeric_limits<double>::denorm_min(), nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<PT<double>> hard = {
      {0, 0, 0, 1, 0, 0, 0, 2},                      // coincident centres
      {3, 4, 0, 2, 0, 0, 0, 3},                      // exact grazing: contact, depth 0
      {3, 4, 0, 2 - 0x1.0p-50, 0, 0, 0, 3},          // one ulp of 5 apart: no contact
      {0, 0, 0, 1, den, 0, 0, 1},                    // the square underflows: coincident path
      {1e160, 0, 0, 1, -1e160, 0, 0, 1},             // d^2 overflows: d = inf, no contact
      {nan, 0, 0, 1, 0, 0, 0, 1},                    // NaN: a contact, as in ODE
  };
  expectBitEqual(hard, /*anyNaN=*/true);
  const auto got = kernel(hard);
  EXPECT_TRUE(got[0].hit && got[1].hit && !got[2].hit && got[3].hit && !got[4].hit && got[5].hit);
  EXPECT_EQ(bits(got[1].depth), 0u);  // +0
  EXPECT_EQ(got[3].nx, 1.0);
}
