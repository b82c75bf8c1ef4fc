#pragma once
// A seeded random batch for the host's tests: spheres with centres uniform in
// [-extent, extent]^3 and radii uniform in [rMin, rMax], then random index pairs.
#include <cstdint>
#include <random>

#include "batch/batch.hpp"

namespace collide::test {

struct BatchShape {
  double extent = 1.0, rMin = 0.05, rMax = 0.4;
};

inline void randomBatch(std::uint64_t seed, std::size_t spheres, std::size_t pairs, SphereTable& t, PairList& p,
                        BatchShape shape = {}) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-shape.extent, shape.extent), rad(shape.rMin, shape.rMax);
  for (std::size_t k = 0; k < spheres; ++k) t.push(pos(rng), pos(rng), pos(rng), rad(rng));
  if (spheres == 0) return;
  std::uniform_int_distribution<std::uint32_t> idx(0, static_cast<std::uint32_t>(spheres - 1));
  for (std::size_t k = 0; k < pairs; ++k) p.push(idx(rng), idx(rng));
}

}  // namespace collide::test
