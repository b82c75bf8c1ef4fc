#pragma once
// ODE's own broad phase for world mode: the spheres as dSphere geoms in a hash space
// (dHashSpace, ODE's default levels), a sweep-and-prune space (dSweepAndPruneSpace, axes x, y,
// z) or a quadtree space (dQuadTreeSpace over x and y, z up: its root block the spheres' box,
// its depth quadTreeDepth below), and dSpaceCollide. The near callback only records the pair;
// the narrow phase (dCollide on the same geoms, OdeBackend) runs after it, so the two are
// timed apart.
#include <exception>
#include <string>
#include <vector>

#include <ode/ode.h>

#include "batch/sane_ranges.hpp"
#include "ode/ode_library.hpp"
#include "world/broad_phase.hpp"

namespace collide::world {

using limits::OdeSpaceKind;

class OdeSpaceBroadPhase final : public BroadPhase {
 public:
  explicit OdeSpaceBroadPhase(OdeSpaceKind kind);
  ~OdeSpaceBroadPhase() override;
  OdeSpaceBroadPhase(const OdeSpaceBroadPhase&) = delete;
  OdeSpaceBroadPhase& operator=(const OdeSpaceBroadPhase&) = delete;

  std::string name() const override { return std::string("ode ") + toString(kind_); }
  // Creates a geom per member the first time (a table of another size starts over), else
  // moves them to the table's values, which marks them dirty as a simulation step would.
  void prepare(const SphereTable& s, const std::vector<std::uint32_t>& members) override;
  void findPairs(const SphereTable& s, const std::vector<std::uint32_t>& members, PairList& out) override;
  // The geoms by sphere index (null for spheres not in the space), for OdeBackend::useGeoms:
  // the same object for the phase's life, its contents set by prepare.
  const std::vector<dGeomID>& geoms() const { return geoms_; }
  // The quadtree's depth for n spheres whose box is `edge` wide (the larger of x and y) and
  // whose median radius is rMedian: 4^depth leaf blocks, at most n / 8 of them and each at
  // least four median diameters wide (a geom lives in the deepest block that holds its box
  // whole), at least 1 and at most 10.
  static int quadTreeDepth(std::size_t n, double edge, double rMedian);

 private:
  static void nearCallback(void* self, dGeomID o1, dGeomID o2);
  void clearGeoms();

  ode::Library lib_;
  OdeSpaceKind kind_;
  dSpaceID space_ = nullptr;
  double quadBox_[7] = {};  // a quadtree's centre, half extents and depth: a new one starts over
  std::vector<dGeomID> geoms_;  // by sphere index; nullptr for spheres not in the space
  PairList* out_ = nullptr;     // the near callback's destination during findPairs
  // An exception in the callback (out of memory) waits here: unwinding through dSpaceCollide
  // would leave the space locked, and ODE aborts when a locked space is destroyed.
  std::exception_ptr error_;
};

}  // namespace collide::world
