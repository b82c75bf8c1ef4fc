// Pair kinds beyond spheres (docs/pair-kinds.md): each CPU reference against ODE's own function
// and against the Scala golden model's vectors (test/vectors/<kind>-<format>.csv, written by
// collide.pairs.PairVectorsWriter).
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
#include "pairs/capsule_sphere.hpp"
#include "pairs/sphere_plane.hpp"
#include "support/test_seed.hpp"

namespace {

using collide::pairs::collideCapsuleSphere;
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

// ODE's own dCollide on two geoms, its one contact as a reference's.
SpherePlaneContact<double> odeContact(dGeomID a, dGeomID b) {
  dContactGeom g{};
  SpherePlaneContact<double> out;
  if (dCollide(a, b, 1, &g, sizeof(dContactGeom)) == 1) {
    out.hit = true;
    for (int i = 0; i < 3; ++i) {
      out.pos[i] = g.pos[i];
      out.normal[i] = g.normal[i];
    }
    out.depth = g.depth;
  }
  return out;
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
  const auto out = odeContact(s, p);
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

// A golden model's vectors (test/vectors/<kind>-<format>.csv): `inputs` input columns, then
// "hit,px,py,pz,qx,qy,qz,depth", hex floats; `collide` maps a row's inputs to the reference's contact.
template <typename T, typename F>
void expectGoldenVectors(const std::string& file, std::size_t inputs, F collide) {
  const std::string path = std::string(COLLIDE_TEST_VECTORS_DIR) + "/" + file;
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
    ASSERT_EQ(v.size(), inputs + 8) << path << " row " << rows + 1;
    SpherePlaneContact<T> want;
    want.hit = v[inputs] != 0;
    for (int i = 0; i < 3; ++i) {
      want.pos[i] = v[inputs + 1 + i];
      want.normal[i] = v[inputs + 4 + i];
    }
    want.depth = v[inputs + 7];
    const auto got = collide(v.data());
    ASSERT_TRUE(sameContact(got, want)) << path << " row " << rows + 1 << ": " << line << "\n  model " << show(want)
                                        << "\n  ours  " << show(got);
    ++rows;
    hits += got.hit;
  }
  EXPECT_GT(rows, 1000);
  EXPECT_GT(hits, rows / 5);
}

template <typename T>
void expectSpherePlaneVectors(const std::string& file) {
  expectGoldenVectors<T>(file, 8, [](const T* v) { return collideSpherePlane<T>(v, v[3], v + 4); });
}

TEST(SpherePlane, Binary32ReferenceIsTheGoldenModelBitForBit) { expectSpherePlaneVectors<float>("sphere-plane-fp32.csv"); }
TEST(SpherePlane, Binary64ReferenceIsTheGoldenModelBitForBit) { expectSpherePlaneVectors<double>("sphere-plane-fp64.csv"); }

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

// ---- Capsule/sphere -----------------------------------------------------------------------

struct CapsuleSphereCase {
  double c[3], axis[3], lz, rc, s[3], rs;  // axis as given to dRFromZAxis (ODE normalizes it)
};

// ODE's own answer: dCollide on a capsule geom (rotated so its z axis is `axis`) and a sphere
// geom; `axis` gets the axis as ODE keeps it (the rotation's third column), which every
// reference takes.
SpherePlaneContact<double> odeCapsuleSphere(const CapsuleSphereCase& k, double axis[3]) {
  dGeomID cap = dCreateCapsule(nullptr, k.rc, k.lz);
  dGeomSetPosition(cap, k.c[0], k.c[1], k.c[2]);
  dMatrix3 R;
  dRFromZAxis(R, k.axis[0], k.axis[1], k.axis[2]);
  dGeomSetRotation(cap, R);
  const dReal* q = dGeomGetRotation(cap);
  axis[0] = q[2];
  axis[1] = q[6];
  axis[2] = q[10];
  dGeomID sph = dCreateSphere(nullptr, k.rs);
  dGeomSetPosition(sph, k.s[0], k.s[1], k.s[2]);
  const auto out = odeContact(cap, sph);
  dGeomDestroy(cap);
  dGeomDestroy(sph);
  return out;
}

// Named cases (ends, caps, the axis itself, a zero length), then random capsules with a sphere
// along the axis and beyond its ends, off it by about the radii (a third within 1e-9 of
// touching), at scales from 1e-3 to 1e6.
std::vector<CapsuleSphereCase> capsuleSphereCases(std::uint64_t seed, int n) {
  std::vector<CapsuleSphereCase> cases = {
      {{0, 0, 0}, {0, 0, 1}, 2, 1, {1.5, 0, 0}, 1},     // beside the middle
      {{0, 0, 0}, {0, 0, 1}, 2, 1, {2, 0, 0}, 1},       // touching the side
      {{0, 0, 0}, {0, 0, 1}, 2, 1, {0, 0, 3}, 1},       // touching the +z cap
      {{0, 0, 0}, {0, 0, 1}, 2, 1, {0.5, 0, -2.5}, 1},  // beyond the -z cap
      {{0, 0, 0}, {0, 0, 1}, 2, 1, {0, 0, 0.5}, 0.25},  // centre on the axis: coincident
      {{0, 0, 0}, {1, 0, 0}, 0, 1, {1.5, 0.5, 0}, 1},   // zero length
      {{1, 1, 1}, {1, 1, 1}, 4, 0.5, {2, 1, 1}, 0.75},  // oblique; ODE normalizes the axis
      {{1e5, -2e5, 3e5}, {0, -1, 0}, 10, 0.1, {1e5 + 0.15, -2e5 - 4.9, 3e5}, 0.1},
  };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g(0, 1);
  for (int i = 0; i < n; ++i) {
    const double scale = std::pow(10.0, -3 + (i % 10));
    CapsuleSphereCase k{};
    double a[3], l = 0, w[3];
    for (int x = 0; x < 3; ++x) {
      a[x] = g(rng);
      l += a[x] * a[x];
      k.c[x] = u(rng) * scale;
      w[x] = g(rng);
    }
    for (int x = 0; x < 3; ++x) k.axis[x] = a[x] /= std::sqrt(l);
    k.lz = (u(rng) + 1) * scale / 2;
    k.rc = (u(rng) + 1) * scale / 16;
    k.rs = (u(rng) + 1) * scale / 16;
    const double t = u(rng) * 0.8 * k.lz;
    double wa = w[0] * a[0] + w[1] * a[1] + w[2] * a[2], wl = 0;
    for (int x = 0; x < 3; ++x) {
      w[x] -= wa * a[x];
      wl += w[x] * w[x];
    }
    const double off = (k.rc + k.rs) * ((i % 3 == 0) ? 0.5 + (u(rng) + 1) / 2 : (i % 3 == 1) ? 1 + u(rng) * 1e-9 : (u(rng) + 1) / 2);
    for (int x = 0; x < 3; ++x) k.s[x] = k.c[x] + t * a[x] + off * w[x] / std::sqrt(wl);
    cases.push_back(k);
  }
  return cases;
}

TEST(CapsuleSphere, Binary64ReferenceIsOdesDCollideBitForBit) {
  collide::ode::Library ode;
  const auto cases = capsuleSphereCases(collide::test::testSeed(20261210), 20000);
  int hits = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    double axis[3];
    const auto want = odeCapsuleSphere(cases[i], axis);
    const auto& k = cases[i];
    const auto got = collideCapsuleSphere<double>(k.c, axis, k.lz, k.rc, k.s, k.rs);
    ASSERT_TRUE(sameContact(got, want)) << "case " << i << "\n  ode  " << show(want) << "\n  ours " << show(got);
    hits += got.hit;
  }
  EXPECT_GT(hits, static_cast<int>(cases.size() / 4));
  EXPECT_LT(hits, static_cast<int>(cases.size() * 3 / 4 + 8));
}

template <typename T>
void expectCapsuleSphereVectors(const std::string& file) {
  expectGoldenVectors<T>(file, 12, [](const T* v) { return collideCapsuleSphere<T>(v, v + 3, v[6], v[7], v + 8, v[11]); });
}
TEST(CapsuleSphere, Binary32ReferenceIsTheGoldenModelBitForBit) { expectCapsuleSphereVectors<float>("capsule-sphere-fp32.csv"); }
TEST(CapsuleSphere, Binary64ReferenceIsTheGoldenModelBitForBit) { expectCapsuleSphereVectors<double>("capsule-sphere-fp64.csv"); }

// Binary32 against binary64 on the same binary32 inputs. With u = 2^-24, M the largest
// coordinate (at least 1) and L the length: alpha takes a difference, a product and two sums
// (at most four roundings of terms up to 2M each, so off by a few u M); clamping does not add
// to that; p = c + alpha a is then off by a few u (M + L). The sphere step (as in
// test_simd_vs_ode.cpp) moves the normal by a few u (M' / d + 1), the position by a few u M' plus
// the radii times that, the depth by a few u (M' + radii), M' = M + L. "A few" is 16 here; pairs
// within 1e-6 of touching (relative to M') may decide differently and are not compared.
TEST(CapsuleSphere, Binary32StaysWithinItsStatedBoundOfBinary64) {
  collide::ode::Library ode;
  const auto cases = capsuleSphereCases(collide::test::testSeed(20261211), 20000);
  const double u = std::ldexp(1.0, -24), c = 16;
  int compared = 0, skipped = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    double axisD[3];
    odeCapsuleSphere(cases[i], axisD);
    const auto& k = cases[i];
    float cf[3], af[3], sf[3];
    double cd[3], ad[3], sd[3];
    for (int x = 0; x < 3; ++x) {
      cd[x] = cf[x] = static_cast<float>(k.c[x]);
      ad[x] = af[x] = static_cast<float>(axisD[x]);
      sd[x] = sf[x] = static_cast<float>(k.s[x]);
    }
    const float lzf = static_cast<float>(k.lz), rcf = static_cast<float>(k.rc), rsf = static_cast<float>(k.rs);
    const auto f = collideCapsuleSphere<float>(cf, af, lzf, rcf, sf, rsf);
    const auto d = collideCapsuleSphere<double>(cd, ad, lzf, rcf, sd, rsf);
    double m = 1;
    for (int x = 0; x < 3; ++x) m = std::max({m, std::fabs(cd[x]), std::fabs(sd[x])});
    m += std::fabs(static_cast<double>(lzf));
    const double rr = static_cast<double>(rcf) + rsf;
    const double gap = rr - d.depth;  // the distance between p and s, less the radii, where d hit
    if (d.hit != f.hit) {
      ASSERT_LT(std::fabs(d.depth), 1e-6 * m) << "case " << i << ": decisions differ away from touching";
      ++skipped;
      continue;
    }
    if (!d.hit) continue;
    const double dist = gap > 0 ? gap : 0;
    const double tolN = c * u * (m / std::max(dist, 1e-300) + 1), tolP = c * u * m + rr * tolN, tolD = c * u * (m + rr);
    ++compared;
    EXPECT_NEAR(f.depth, d.depth, tolD) << "case " << i;
    for (int x = 0; x < 3; ++x) {
      EXPECT_NEAR(f.pos[x], d.pos[x], tolP) << "case " << i << " axis " << x;
      EXPECT_NEAR(f.normal[x], d.normal[x], tolN) << "case " << i << " axis " << x;
    }
  }
  RecordProperty("near_touching_skipped", skipped);
  EXPECT_GT(compared, static_cast<int>(cases.size() / 4));
}

}  // namespace
