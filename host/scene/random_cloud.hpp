#pragma once
// A seeded random cloud of spheres in an axis-aligned box (centres uniform in the box,
// radii uniform in [rMin, rMax]). Same seed, same cloud, on every platform.
#include <cstdint>
#include <vector>

#include "scene/json_reader.hpp"

namespace collide::scene {

struct CloudParams {
  long long count = 100;
  std::uint64_t seed = 1;
  Vec3 min{-1, -1, -1}, max{1, 1, 1};
  double rMin = 0.05, rMax = 0.1;
};

struct CloudSphere {
  Vec3 centre;
  double radius;
};

std::vector<CloudSphere> randomCloud(const CloudParams& p);

}  // namespace collide::scene
