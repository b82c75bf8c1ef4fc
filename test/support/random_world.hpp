#pragma once
// Seeded sphere worlds for the world-mode tests (test only). Every value is a binary32 value,
// so the simd (binary32) and ode (binary64) backends see the same spheres.
#include <cmath>
#include <cstdint>
#include <random>

#include "batch/batch.hpp"

namespace collide::test {

struct WorldShape {
  std::size_t spheres = 1000;
  double extent = 10;             // centres in [-extent, extent]^3 (negative coordinates too)
  double rMin = 0.3, rMax = 0.7;  // radii uniform in [rMin, rMax]...
  bool logRadii = false;          // ...or log-uniform (mixed sizes: rMax / rMin = 1000)
};

inline SphereTable randomWorld(std::uint64_t seed, const WorldShape& w) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-w.extent, w.extent), u(0, 1);
  SphereTable t;
  for (std::size_t k = 0; k < w.spheres; ++k) {
    const double r = w.logRadii ? w.rMin * std::pow(w.rMax / w.rMin, u(rng)) : w.rMin + (w.rMax - w.rMin) * u(rng);
    auto f = [](double v) { return static_cast<double>(static_cast<float>(v)); };
    t.push(f(pos(rng)), f(pos(rng)), f(pos(rng)), f(r));
  }
  return t;
}

}  // namespace collide::test
