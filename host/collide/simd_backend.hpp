#pragma once
// `simd` backend: gathers each pair's spheres to binary32 SoA and runs the vectorized
// dCollideSpheres kernel (simd_kernel.cpp). Results are exact binary32 values.
#include <vector>

#include "collide/backend.hpp"

namespace collide {

class SimdBackend final : public CollisionBackend {
 public:
  std::string name() const override { return "simd"; }
  LinkFormat format() const override { return LinkFormat::Binary32; }
  void collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) override;

 private:
  // Scratch reused across batches so a step does not allocate.
  std::vector<float> in_[8];
  std::vector<float> res_[7];
  std::vector<std::uint8_t> hit_;
};

}  // namespace collide
