#include "scene/diamond.hpp"

#include <cmath>

namespace collide::scene {

long long diamondSphereCount(int h) { return static_cast<long long>(h) * (2LL * h * h + 1) / 3; }

namespace {
double dbtwnball(const DiamondParams& p) {
  const double hip = std::sqrt((2 * p.radius) * (2 * p.radius) + (2 * p.radius) * (2 * p.radius));
  return hip - 2 * p.radius + p.dSph;
}
}  // namespace

std::vector<Vec3> diamondCentres(const DiamondParams& p) {
  const double db = dbtwnball(p);
  const double a = db / 2 + p.radius;
  std::vector<Vec3> out;
  out.reserve(static_cast<std::size_t>(diamondSphereCount(p.hMax)));
  for (int step = 0; step < 2 * p.hMax - 1; ++step) {
    const int n = step < p.hMax ? step + 1 : 2 * p.hMax - 1 - step;
    const double z = step * db + 2 * p.radius + 4;
    for (int u = 0; u < n; ++u)
      for (int v = 0; v < n; ++v) out.push_back({(u - v) * a, (u + v - (n - 1)) * a, z});
  }
  return out;
}

Vec3 diamondCentre(const DiamondParams& p) {
  return {0.0, 0.0, (p.hMax - 1) * dbtwnball(p) + 2 * p.radius + 4};
}

}  // namespace collide::scene
