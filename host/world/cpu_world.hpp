#pragma once
// World mode on the CPU as a WorldEngine: our grid broad phase and the simd kernel (the
// pipeline of `collide spheres --backend simd`).
#include "collide/simd_backend.hpp"
#include "world/grid_broad_phase.hpp"
#include "world/world_collider.hpp"
#include "world/world_engine.hpp"

namespace collide::world {

class CpuWorld final : public WorldEngine {
 public:
  CpuWorld() : collider_(grid_, simd_) {}
  std::string name() const override { return "simd (grid + binary32 kernel)"; }
  void collide(const SphereTable& s, WorldContacts& out, WorldTiming& time) override { collider_.collide(s, out, time); }

 private:
  GridBroadPhase grid_;
  SimdBackend simd_;
  WorldCollider collider_;
};

}  // namespace collide::world
