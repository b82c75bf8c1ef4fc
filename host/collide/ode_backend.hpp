#pragma once
// `ode` backend: ODE's own dCollide on dSphere geoms (binary64, Debian's libode is
// double precision). Uses the world's geoms when the sphere table carries them, else
// two scratch geoms repositioned per pair (vector mode).
#include "collide/backend.hpp"
#include "ode/ode_library.hpp"

namespace collide {

class OdeBackend final : public CollisionBackend {
 public:
  OdeBackend();
  ~OdeBackend() override;
  OdeBackend(const OdeBackend&) = delete;
  OdeBackend& operator=(const OdeBackend&) = delete;

  std::string name() const override { return "ode"; }
  LinkFormat format() const override { return LinkFormat::Binary64; }
  void collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) override;

 private:
  ode::Library lib_;  // keeps ODE initialised while scratch geoms exist
  dGeomID scratch1_, scratch2_;
};

}  // namespace collide
