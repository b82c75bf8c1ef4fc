#pragma once
// Seeded world-mode test worlds shared by the tests of every broad phase that must give simd's
// contacts (test_tuned_grid, test_engine_broad_phases): uniform, clustered and mixed-radius
// worlds with touching pairs nudged by ulps and coincident centres added, bad spheres, and
// the grid's corner cases. Every value is a binary32 value unless a case says otherwise.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "support/random_world.hpp"

namespace collide::test {

inline double f32(double v) { return static_cast<double>(static_cast<float>(v)); }

// Gaussian clusters of about 100 spheres, radii log-uniform over [rMin, rMax].
inline SphereTable clusteredWorld(std::uint64_t seed, std::size_t n, double rMin, double rMax) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), pos(-20, 20);
  const std::size_t clusters = std::max<std::size_t>(1, n / 100);
  std::vector<std::array<double, 3>> c(clusters);
  for (auto& k : c) k = {pos(rng), pos(rng), pos(rng)};
  std::normal_distribution<double> g(0, 1.5);
  SphereTable t;
  for (std::size_t k = 0; k < n; ++k) {
    const auto& cc = c[k % clusters];
    t.push(f32(cc[0] + g(rng)), f32(cc[1] + g(rng)), f32(cc[2] + g(rng)), f32(rMin * std::pow(rMax / rMin, u(rng))));
  }
  return t;
}

// Pairs at binary32's edge: spheres placed at r1 + r2 from others along an axis or a random
// direction, nudged by a few ulps either way, and spheres on another's centre.
inline void addTouchingAndCoincident(std::uint64_t seed, SphereTable& t, std::size_t count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const std::size_t n = t.size();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t a = static_cast<std::size_t>(u(rng) * n) % n;
    const double r = f32(t.r[a] * (0.5 + u(rng)));
    const int kind = static_cast<int>(u(rng) * 4);
    if (kind == 0) {  // coincident
      t.push(t.x[a], t.y[a], t.z[a], r);
      continue;
    }
    const float reach = static_cast<float>(t.r[a]) + static_cast<float>(r);
    double dir[3] = {1, 0, 0};
    if (kind == 2) {
      for (double& d : dir) d = u(rng) - 0.5;
      const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
      for (double& d : dir) d /= len;
    }
    float x = static_cast<float>(t.x[a] + dir[0] * reach), y = static_cast<float>(t.y[a] + dir[1] * reach),
          z = static_cast<float>(t.z[a] + dir[2] * reach);
    const int nudge = static_cast<int>(u(rng) * 5) - 2;  // -2 .. 2 ulps along x
    for (int s = 0; s < std::abs(nudge); ++s)
      x = std::nextafter(x, nudge > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity());
    t.push(x, y, z, r);
  }
}

struct WorldCase {
  std::string name;
  SphereTable spheres;
};

// Uniform, clustered, clustered with radii 0.05-2, radii 1:1000, each with 400 touching or
// coincident spheres added; touching pairs of equal spheres; three bad spheres in the first.
inline std::vector<WorldCase> randomWorldCases(std::uint64_t seed) {
  std::vector<WorldCase> cases;
  WorldShape uniform;
  uniform.spheres = 3000;
  uniform.extent = 12;
  cases.push_back({"uniform", randomWorld(seed, uniform)});
  cases.push_back({"clustered", clusteredWorld(seed + 1, 3000, 0.3, 0.5)});
  cases.push_back({"clustered, mixed radii 0.05-2", clusteredWorld(seed + 2, 3000, 0.05, 2)});
  WorldShape mixed;
  mixed.spheres = 2500;
  mixed.rMin = 0.001;
  mixed.rMax = 1;
  mixed.logRadii = true;
  cases.push_back({"mixed radii 1:1000", randomWorld(seed + 3, mixed)});
  for (auto& c : cases) addTouchingAndCoincident(seed + 4, c.spheres, 400);
  // Equal spheres in touching pairs along an axis (d = r1 + r2 = the cut diameter, the
  // cell edge's own case), some nudged an ulp closer, at random places.
  std::mt19937_64 rng(seed + 5);
  std::uniform_real_distribution<double> u(-40, 40);
  SphereTable pairs;
  for (int k = 0; k < 3000; ++k) {
    float a[3] = {static_cast<float>(u(rng)), static_cast<float>(u(rng)), static_cast<float>(u(rng))};
    float b[3] = {a[0], a[1], a[2]};
    b[k % 3] += 1.0f;  // d = 1 exactly: both are multiples of the ulp of a, under 64
    if (k % 5 == 0) b[k % 3] = std::nextafter(b[k % 3], a[k % 3]);
    pairs.push(a[0], a[1], a[2], 0.5);
    pairs.push(b[0], b[1], b[2], 0.5);
  }
  cases.push_back({"touching pairs of equal spheres", pairs});
  // Bad spheres among them: listed, never collided.
  cases[0].spheres.push(std::nan(""), 0, 0, 1);
  cases[0].spheres.push(0, 0, 0, -1);
  cases[0].spheres.push(2e6, 0, 0, 1);
  return cases;
}

// The grid's corner cases: nothing, one sphere, everything at one point, a sphere 50 cells
// across, many large spheres, negative and denormal centres on cell boundaries, tiny radii (one
// that rounds to binary32 zero), and centres 2e6 m apart with tiny radii.
inline std::vector<WorldCase> cornerWorldCases() {
  std::vector<WorldCase> cases;
  cases.push_back({"empty", {}});
  SphereTable one;
  one.push(1, 2, 3, 0.5);
  cases.push_back({"one sphere", one});
  SphereTable point;
  for (int k = 0; k < 60; ++k) point.push(0.25, -0.5, 3, 0.1 + 0.01 * k);
  cases.push_back({"60 at one point", point});
  SphereTable big = randomWorld(11, {800, 10, 0.2, 0.3, false});
  big.push(0, 0, 0, 15);
  cases.push_back({"a sphere 50 cells across", big});
  SphereTable many = randomWorld(12, {1500, 10, 0.05, 0.1, false});
  for (int k = 0; k < 40; ++k) many.push(f32(-9 + 0.45 * k), f32(0.3 * k - 6), 0, 1.5 + 0.05 * k);
  cases.push_back({"40 large spheres", many});
  SphereTable edges;
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z) edges.push(0.5 * x, 0.5 * y, 0.5 * z, 0.25);
  edges.push(-0x1p-140, 0, 0, 0.25);
  edges.push(0x1p-140, 0x1p-149, -0x1p-149, 0.25);
  cases.push_back({"cell boundaries, negative, denormal", edges});
  SphereTable tiny;
  for (int k = 0; k < 200; ++k) tiny.push(f32(1e-6 * k), f32(1e-6 * (k % 7)), 0, 1e-6);
  tiny.push(0, 0, 0, 1e-300);  // rounds to binary32 zero: touches only what it coincides with
  cases.push_back({"tiny radii", tiny});
  SphereTable far;
  for (int k = 0; k < 300; ++k) {
    const double base = (k % 3 - 1) * 1e6;
    far.push(f32(base + 1e-3 * (k / 3)), f32(-base), f32(base * (k % 2)), 6e-4);
  }
  cases.push_back({"2e6 m apart, tiny radii", far});
  return cases;
}

}  // namespace collide::test
