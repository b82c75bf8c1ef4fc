#pragma once
// Equal spheres stacked at rest by construction, for stability studies (scenes/rest_pile.json,
// scenes/rest_stack.json): square layers of touching spheres on a floor, each next layer in
// the hollows of the one below (face-centred cubic stacking along z: layer spacing r sqrt 2).
//  - block: layers alternate nx x ny and (nx-1) x (ny-1) spheres, all inside the base's
//    footprint, so four walls at the footprint's edges hold every A layer (a pile in a box);
//  - pyramid: layer l has (nx-l) x (ny-l) spheres (a cannonball stack), layers until one is empty
//    or `layers` are placed; walls at the footprint's edges frame its base.
// Every nearest-neighbour pair touches exactly in real arithmetic (distance 2r).
#include <vector>

#include "scene/json_reader.hpp"

namespace collide::scene {

struct StackedPileParams {
  enum class Shape { Block, Pyramid };
  Shape shape = Shape::Block;
  int nx = 4, ny = 4, layers = 4;
  double radius = 0.05;
  Vec3 corner{0, 0, 0};  // the footprint's lower corner, on the floor (z = corner z)
};

std::vector<Vec3> stackedPileCentres(const StackedPileParams& p);

}  // namespace collide::scene
