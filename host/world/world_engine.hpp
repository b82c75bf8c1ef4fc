#pragma once
// Whatever does a world's whole sphere/sphere collision in one call (a scene with
// "collision": {"offload": "world"}): the CPU grid with the simd kernel, or the AFU's world
// mode. Contacts as WorldCollider gives them (sorted by (i, j), bad spheres listed).
#include <string>

#include "world/world_collider.hpp"

namespace collide::world {

class WorldEngine {
 public:
  virtual ~WorldEngine() = default;
  virtual std::string name() const = 0;
  // `time`: the engine's own account, broadNs the broad phase, narrowNs the rest of the call
  // (measured on the CPU; modelled on the AFU, where the co-simulation's wall time is no cost).
  virtual void collide(const SphereTable& s, WorldContacts& out, WorldTiming& time) = 0;
  // Whether `time` is modelled (the AFU) rather than measured.
  virtual bool modelled() const { return false; }
};

}  // namespace collide::world
