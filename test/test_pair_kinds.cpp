// Pair kinds beyond spheres (docs/pair-kinds.md): each CPU reference against ODE's own function
// and against the Scala golden model's vectors (test/vectors/sphere-plane-*.csv, written by
// collide.pairs.SpherePlaneVectorsWriter).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <ode/ode.h>

#include "ode/ode_library.hpp"
#include "pairs/sphere_plane.hpp"
#include "support/test_seed.hpp"

namespace {

using collide::pairs::collideSpherePlane;
using collide::pairs::SpherePlaneContact;

template <typename T>
bool sameBits(T a, T b) {
  if (std::isnan(a) && std::isnan(b)) return true;  // NaN payloads are the CPU's, not ODE's order
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

template <typename T>
std::string show(const SpherePlaneContact<T>& c) {
  std::ostringstream o;
  o << std::hexfloat << "hit=" << c.hit << " pos=(" << c.pos[0] << "," << c.pos[1] << "," << c.pos[2] << ") n=("
    << c.normal[0] << "," << c.normal[1] << "," << c.normal[2] << ") depth=" << c.depth;
  return o.str();
}

template <typename T>
bool sameContact(const SpherePlaneContact<T>& a, const SpherePlaneContact<T>& b) {
  if (a.hit != b.hit) return false;
  for (int i = 0; i < 3; ++i)
    if (!sameBits(a.pos[i], b.pos[i]) || !sameBits(a.normal[i], b.normal[i])) return false;
  return sameBits(a.depth, b.depth);
}

struct SpherePlaneCase {
  double c[3];
  double r;
  double plane[4];  // as given to dCreatePlane (ODE normalizes it)
};

// ODE's own answer: dCollide on a sphere geom and a plane geom; `params` gets the plane as ODE
// keeps it (normalized), the input every reference takes.
SpherePlaneContact<double> odeSpherePlane(const SpherePlaneCase& k, double params[4]) {
  dGeomID s = dCreateSphere(nullptr, k.r);
  dGeomSetPosition(s, k.c[0], k.c[1], k.c[2]);
  dGeomID p = dCreatePlane(nullptr, k.plane[0], k.plane[1], k.plane[2], k.plane[3]);
  dVector4 q;
  dGeomPlaneGetParams(p, q);
  for (int i = 0; i < 4; ++i) params[i] = q[i];
  dContactGeom g{};
  SpherePlaneContact<double> out;
  if (dCollide(s, p, 1, &g, sizeof(dContactGeom)) == 1) {
    out.hit = true;
    for (int i = 0; i < 3; ++i) {
      out.pos[i] = g.pos[i];
      out.normal[i] = g.normal[i];
    }
    out.depth = g.depth;
  }
  dGeomDestroy(s);
  dGeomDestroy(p);
  return out;
}

// Named hard cases, then random spheres about random planes (a third grazing, a third touching
// up to rounding), at scales from 1e-3 to 1e6.
std::vector<SpherePlaneCase> spherePlaneCases(std::uint64_t seed, int n) {
  const double s = 1 / std::sqrt(3.0);
  std::vector<SpherePlaneCase> cases = {
      {{0, 0, 1}, 1, {0, 0, 1, 0}},            // touching: depth exactly 0
      {{0.25, -3, 0.5}, 1, {0, 0, 1, 0}},      // sunk by half its radius
      {{2, 3, 0}, 0.75, {0, 0, 1, 0}},         // the plane through the centre
      {{0, 0, -5}, 1, {0, 0, 1, 0}},           // centre below the plane
      {{9.5, 0, 0}, 1, {-1, 0, 0, -10}},       // a wall facing -x
      {{1, 1, 1}, 1, {s, s, s, 1}},            // oblique
      {{10, 10, 10}, 1, {1, 1, 1, 1}},         // oblique, far side; ODE normalizes (1, 1, 1, 1)
      {{3, 4, 0}, 0, {0, 0, 1, 0}},            // zero radius on the plane
      {{0, 0, 1e4 - 0.5}, 1, {0, 0, 1, 1e4}},  // an offset far from the origin
      {{3e30, 0, 1e30}, 2e30, {0, 0, 1, 0}},   // very large
      {{0, 0, 1e-30}, 2e-30, {0, 0, 1, 0}},    // very small
      {{1, 2, 3}, 1, {0, 0, 0, 5}},            // a zero normal: ODE makes it (1, 0, 0, 0)
  };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g(0, 1);
  for (int i = 0; i < n; ++i) {
    const double scale = std::pow(10.0, -3 + (i % 10));
    SpherePlaneCase k{};
    double l = 0;
    for (int a = 0; a < 3; ++a) {
      k.plane[a] = g(rng);
      l += k.plane[a] * k.plane[a];
      k.c[a] = u(rng) * scale;
    }
    k.r = (u(rng) + 1) * scale / 8;
    double dot = 0;
    for (int a = 0; a < 3; ++a) dot += k.c[a] * k.plane[a] / std::sqrt(l);
    const double gap = (i % 3 == 0) ? u(rng) * k.r : (i % 3 == 1) ? u(rng) * k.r * 1e-9 : 0.0;
    k.plane[3] = (dot - k.r + gap) * std::sqrt(l);
    cases.push_back(k);
  }
  return cases;
}

TEST(SpherePlane, Binary64ReferenceIsOdesDCollideBitForBit) {
  collide::ode::Library ode;
  const auto cases = spherePlaneCases(collide::test::testSeed(20261208), 20000);
  int hits = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    double params[4];
    const auto want = odeSpherePlane(cases[i], params);
    const auto got = collideSpherePlane<double>(cases[i].c, cases[i].r, params);
    ASSERT_TRUE(sameContact(got, want)) << "case " << i << "\n  ode  " << show(want) << "\n  ours " << show(got);
    hits += got.hit;
  }
  // Both outcomes well represented, so the comparison covers both branches.
  EXPECT_GT(hits, static_cast<int>(cases.size() / 4));
  EXPECT_LT(hits, static_cast<int>(cases.size() * 3 / 4 + 12));
}

// The golden model's vectors: "cx,...,d,hit,px,py,pz,qx,qy,qz,depth" as hex floats.
template <typename T>
void expectGoldenVectors(const std::string& name) {
  const std::string path = std::string(COLLIDE_TEST_VECTORS_DIR) + "/sphere-plane-" + name + ".csv";
  std::ifstream in(path);
  ASSERT_TRUE(in) << "cannot read " << path;
  std::string line;
  std::getline(in, line);
  int rows = 0, hits = 0;
  while (std::getline(in, line)) {
    std::vector<T> v;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) v.push_back(static_cast<T>(std::strtod(cell.c_str(), nullptr)));
    ASSERT_EQ(v.size(), 16u) << path << " row " << rows + 1;
    const T c[3] = {v[0], v[1], v[2]};
    const T plane[4] = {v[4], v[5], v[6], v[7]};
    SpherePlaneContact<T> want;
    want.hit = v[8] != 0;
    for (int i = 0; i < 3; ++i) {
      want.pos[i] = v[9 + i];
      want.normal[i] = v[12 + i];
    }
    want.depth = v[15];
    const auto got = collideSpherePlane<T>(c, v[3], plane);
    ASSERT_TRUE(sameContact(got, want)) << path << " row " << rows + 1 << ": " << line << "\n  model " << show(want)
                                        << "\n  ours  " << show(got);
    ++rows;
    hits += got.hit;
  }
  EXPECT_GT(rows, 1000);
  EXPECT_GT(hits, rows / 5);
}

TEST(SpherePlane, Binary32ReferenceIsTheGoldenModelBitForBit) { expectGoldenVectors<float>("fp32"); }
TEST(SpherePlane, Binary64ReferenceIsTheGoldenModelBitForBit) { expectGoldenVectors<double>("fp64"); }

// Binary32 against binary64 on the same binary32 inputs (the plane as ODE keeps it, rounded as
// the host sends it). Every value of depth = (d - ((cx nx + cy ny) + cz nz)) + r goes through at
// most five roundings, so |depth32 - depth64| <= (g5(2^-24) + g5(2^-53)) S with
// S = |d| + |r| + sum |ci ni| and g5(u) = 5u / (1 - 5u); the decisions differ only where
// |depth64| is within that; pos = c - n r takes two roundings: g2 (|ci| + |ni r|) each.
TEST(SpherePlane, Binary32StaysWithinItsStatedBoundOfBinary64) {
  collide::ode::Library ode;
  const auto cases = spherePlaneCases(collide::test::testSeed(20261209), 20000);
  const auto gamma = [](int n, double u) { return n * u / (1 - n * u); };
  const double u32 = std::ldexp(1.0, -24), u64 = std::ldexp(1.0, -53);
  int differ = 0, both = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    double params[4];
    odeSpherePlane(cases[i], params);
    float cf[3], pf[4], rf = static_cast<float>(cases[i].r);
    double cd[3], pd[4], rd = rf;
    for (int a = 0; a < 3; ++a) cd[a] = cf[a] = static_cast<float>(cases[i].c[a]);
    for (int a = 0; a < 4; ++a) pd[a] = pf[a] = static_cast<float>(params[a]);
    const auto f = collideSpherePlane<float>(cf, rf, pf);
    const auto d = collideSpherePlane<double>(cd, rd, pd);
    double sum = std::fabs(pd[3]) + std::fabs(rd);
    for (int a = 0; a < 3; ++a) sum += std::fabs(cd[a] * pd[a]);
    const double bound = (gamma(5, u32) + gamma(5, u64)) * sum;
    const double depth64 = pd[3] - (cd[0] * pd[0] + cd[1] * pd[1] + cd[2] * pd[2]) + rd;
    if (f.hit != d.hit) {
      ASSERT_LE(std::fabs(depth64), bound) << "case " << i << ": decisions differ beyond the bound";
      ++differ;
      continue;
    }
    if (!f.hit) continue;
    ++both;
    ASSERT_LE(std::fabs(f.depth - d.depth), bound) << "case " << i;
    for (int a = 0; a < 3; ++a) {
      const double pb = (gamma(2, u32) + gamma(2, u64)) * (std::fabs(cd[a]) + std::fabs(pd[a] * rd));
      ASSERT_LE(std::fabs(f.pos[a] - d.pos[a]), pb) << "case " << i << " axis " << a;
      ASSERT_EQ(static_cast<double>(f.normal[a]), d.normal[a]) << "case " << i;
    }
  }
  RecordProperty("decisions_differ", differ);
  EXPECT_GT(both, static_cast<int>(cases.size() / 4));
}

}  // namespace
