#include "scene/stacked_pile.hpp"

#include <cmath>

namespace collide::scene {

std::vector<Vec3> stackedPileCentres(const StackedPileParams& p) {
  std::vector<Vec3> out;
  const double r = p.radius, h = r * std::sqrt(2.0);
  for (int l = 0; l < p.layers; ++l) {
    // Block: B layers (odd l) sit one radius in from the A layers; pyramid: each layer one
    // radius in from the one below.
    const int in = p.shape == StackedPileParams::Shape::Block ? l % 2 : l;
    const int nx = p.nx - in, ny = p.ny - in;
    if (nx <= 0 || ny <= 0) break;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        out.push_back({p.corner[0] + (2 * i + 1 + in) * r, p.corner[1] + (2 * j + 1 + in) * r, p.corner[2] + r + l * h});
  }
  return out;
}

}  // namespace collide::scene
