#pragma once
// The paper's diamond benchmark (Alves et al.; docs/host.md, "Diamond geometry"):
// layers of size 1..hMax..1, layer of size n an n x n square lattice rotated 45 degrees.
// r = 0.1; hip = sqrt((2r)^2 + (2r)^2); dbtwnball = hip - 2r + dSph; in-layer step
// a = dbtwnball/2 + r; layer z = step*dbtwnball + 2r + 4 (step = 0 .. 2hMax-2).
// Lattice point (u, v) of a layer of size n sits at x = (u - v)a, y = (u + v - (n-1))a:
// the 45-degree rotation of the lattice, centred on the z axis. (Our reading of the
// formulas; at dSph = 0 in-layer neighbours touch, d = a*sqrt(2) = 2r.)
#include <vector>

#include "scene/json_reader.hpp"

namespace collide::scene {

struct DiamondParams {
  int hMax = 10;
  double dSph = 0.0;
  double radius = 0.1;  // the paper's r
};

long long diamondSphereCount(int hMax);  // hMax(2hMax^2 + 1)/3
std::vector<Vec3> diamondCentres(const DiamondParams& p);
Vec3 diamondCentre(const DiamondParams& p);  // (0, 0, middle layer's z)

}  // namespace collide::scene
