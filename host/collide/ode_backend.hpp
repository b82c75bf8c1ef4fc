#pragma once
// `ode` backend: ODE's own dCollide on dSphere geoms (binary64, Debian's libode is
// double precision). Collides the spheres' own geoms when the ODE side has bound them
// (useGeoms: a simulation's world, an ODE space), else two scratch geoms repositioned per
// pair (vector mode). The geoms live here, not in SphereTable, so that only this backend and
// the ODE side depend on ODE.
#include <vector>

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

  // The geoms of the tables collide() will see, by sphere index (not owned; null or empty:
  // the scratch geoms). A non-empty set must match the table's size.
  void useGeoms(const std::vector<dGeomID>* geoms) { geoms_ = geoms; }

 private:
  ode::Library lib_;  // keeps ODE initialised while scratch geoms exist
  dGeomID scratch1_, scratch2_;
  const std::vector<dGeomID>* geoms_ = nullptr;
};

// Binds geoms to an ode backend for one scope (e.g. one step), so that a backend serving
// several worlds never keeps another's geoms, nor dangling ones.
class OdeGeomBinding {
 public:
  OdeGeomBinding(OdeBackend* backend, const std::vector<dGeomID>& geoms) : backend_(backend) {
    if (backend_) backend_->useGeoms(&geoms);
  }
  ~OdeGeomBinding() {
    if (backend_) backend_->useGeoms(nullptr);
  }
  OdeGeomBinding(const OdeGeomBinding&) = delete;
  OdeGeomBinding& operator=(const OdeGeomBinding&) = delete;

 private:
  OdeBackend* backend_;
};

}  // namespace collide
