#pragma once
// The data a collision backend works on: a sphere table and a list of index pairs
// (the AFU's own view, docs/afu-interface.md), both structure-of-arrays.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/link_format.hpp"

namespace collide {

struct SphereTable {
  // Plain numbers only: the layers below the backends (driver, link, format, world grid)
  // need no ODE. The ode backend gets a world's geoms from the ODE side (OdeBackend::useGeoms).
  std::vector<double> x, y, z, r;

  std::size_t size() const { return x.size(); }
  void clear() { x.clear(); y.clear(); z.clear(); r.clear(); }
  void push(double px, double py, double pz, double pr) {
    x.push_back(px); y.push_back(py); z.push_back(pz); r.push_back(pr);
  }
};

// Pair k is (sphere i[k], sphere j[k]); the normal points from j to i, as in
// ODE's dCollideSpheres(o1 = i, o2 = j).
struct PairList {
  std::vector<std::uint32_t> i, j;
  std::size_t size() const { return i.size(); }
  void clear() { i.clear(); j.clear(); }
  void push(std::uint32_t a, std::uint32_t b) { i.push_back(a); j.push_back(b); }
};

}  // namespace collide
