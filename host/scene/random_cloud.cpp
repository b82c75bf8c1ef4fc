#include "scene/random_cloud.hpp"

#include <random>

namespace collide::scene {

std::vector<CloudSphere> randomCloud(const CloudParams& p) {
  std::mt19937_64 rng(p.seed);
  // 53 random bits -> [0, 1); our own mapping, so the cloud does not depend on the
  // standard library's distribution implementation.
  auto unit = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  std::vector<CloudSphere> out;
  out.reserve(static_cast<std::size_t>(p.count));
  for (long long k = 0; k < p.count; ++k) {
    CloudSphere s;
    for (int c = 0; c < 3; ++c) s.centre[c] = p.min[c] + (p.max[c] - p.min[c]) * unit();
    s.radius = p.rMin + (p.rMax - p.rMin) * unit();
    out.push_back(s);
  }
  return out;
}

}  // namespace collide::scene
