#pragma once
// Pairs over binary32's whole finite range (test only): 400 a scale at 1e7, 1e30, 3e37, 1,
// 1e-30 and 1e-40 m (subnormal), half of them near each other, every value a binary32.
#include <cstdint>
#include <random>
#include <vector>

#include "batch/batch.hpp"

namespace collide::test {

struct DomainPairs {
  SphereTable spheres;
  PairList pairs;
  std::vector<double> scale;  // per pair
};

inline DomainPairs domainPairs(std::uint64_t seed, int perScale = 400) {
  std::mt19937_64 rng(seed);
  DomainPairs d;
  auto f = [](double v) { return static_cast<double>(static_cast<float>(v)); };
  for (double scale : {1e7, 1e30, 1e-40, 1e-30, 1.0, 3e37}) {
    std::uniform_real_distribution<double> pos(-scale, scale), rad(0.0, scale);
    for (int n = 0; n < perScale; ++n) {
      const double cx = pos(rng), cy = pos(rng), cz = pos(rng);
      const double near = n % 2 ? 0.01 : 1.0;  // contacts likely, or anywhere in the box
      d.spheres.push(f(cx), f(cy), f(cz), f(rad(rng)));
      d.spheres.push(f(cx + near * pos(rng)), f(cy + near * pos(rng)), f(cz + near * pos(rng)), f(rad(rng)));
      d.pairs.push(static_cast<std::uint32_t>(d.spheres.size() - 2), static_cast<std::uint32_t>(d.spheres.size() - 1));
      d.scale.push_back(scale);
    }
  }
  return d;
}

}  // namespace collide::test
