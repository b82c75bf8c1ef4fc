#pragma once
// World mode's broad phase: the candidate sphere pairs of a sphere table, each once as
// (min, max). Two kinds: our grid (grid_broad_phase.hpp) and an ODE space
// (ode_space_broad_phase.hpp), so that `collide spheres` times either the same way.
#include <cstdint>
#include <string>
#include <vector>

#include "batch/batch.hpp"

namespace collide::world {

class BroadPhase {
 public:
  virtual ~BroadPhase() = default;
  virtual std::string name() const = 0;
  // Untimed set-up before findPairs on this table: an ODE space creates or moves its geoms
  // (OdeSpaceBroadPhase::geoms, which the ode narrow phase may be bound to); the grid needs none.
  virtual void prepare(const SphereTable& s, const std::vector<std::uint32_t>& members) = 0;
  // Appends the candidates among `members` (the spheres that may be collided) to `out`.
  virtual void findPairs(const SphereTable& s, const std::vector<std::uint32_t>& members, PairList& out) = 0;
};

}  // namespace collide::world
