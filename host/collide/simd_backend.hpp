#pragma once
// `simd` backend: gathers each pair's spheres to binary32 SoA and runs the vectorized
// dCollideSpheres kernel (simd_kernel.cpp), block by block. Results are exact binary32 values.
// `simd64`: the same kernel in binary64 on the spheres as they are, which is ODE's own
// dCollideSpheres vectorized: the CPU's price of precision, next to binary32's.
#include <vector>

#include "collide/backend.hpp"

namespace collide {

class SimdBackend final : public CollisionBackend {
 public:
  // Binary32 (simd) or Binary64 (simd64); other formats have no CPU kernel.
  explicit SimdBackend(LinkFormat format = LinkFormat::Binary32);
  std::string name() const override { return format_ == LinkFormat::Binary64 ? "simd64" : "simd"; }
  LinkFormat format() const override { return format_; }
  void collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) override;

 private:
  LinkFormat format_;
};

}  // namespace collide
