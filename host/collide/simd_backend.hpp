#pragma once
// `simd` backend: gathers each pair's spheres to binary32 SoA and runs the vectorized
// dCollideSpheres kernel (simd_kernel.cpp), block by block. Results are exact binary32 values.
#include <vector>

#include "collide/backend.hpp"

namespace collide {

class SimdBackend final : public CollisionBackend {
 public:
  std::string name() const override { return "simd"; }
  LinkFormat format() const override { return LinkFormat::Binary32; }
  void collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) override;
};

}  // namespace collide
