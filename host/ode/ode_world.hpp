#pragma once
// The ODE world of a scene: one body + dSphere geom per sphere in a hash space, an
// optional ground plane, and a contact joint group. Owns every ODE object (RAII).
#include <vector>

#include <ode/ode.h>

#include "batch/batch.hpp"
#include "batch/sane_ranges.hpp"
#include "ode/ode_library.hpp"
#include "scene/scene.hpp"

namespace collide::ode {

// An empty space of that kind (sweep and prune on axes x, y, z, ODE's own default order); a
// quadtree needs a box and is refused here (logic_error).
dSpaceID createSpace(limits::OdeSpaceKind kind);

class World {
 public:
  explicit World(const scene::Scene& scene);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  dWorldID world() const { return world_; }
  dSpaceID space() const { return space_; }
  dJointGroupID contacts() const { return contacts_; }
  std::size_t sphereCount() const { return geoms_.size(); }
  dGeomID sphereGeom(std::size_t k) const { return geoms_[k]; }
  const std::vector<dGeomID>& sphereGeoms() const { return geoms_; }  // by sphere index, fixed for the world's life
  dBodyID sphereBody(std::size_t k) const { return bodies_[k]; }
  // dSpaceCollide on the world's space, remembering whether it returned (~World).
  void collideSpace(void* data, dNearCallback* callback);
  // Sphere index of a geom, or -1 for a non-sphere (the ground plane).
  long sphereIndex(dGeomID g) const;

  // Refreshes `table` with the spheres' current centres and radii (their geoms: sphereGeoms).
  void fillSphereTable(SphereTable& table) const;

 private:
  Library lib_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  std::vector<dBodyID> bodies_;
  std::vector<dGeomID> geoms_;
  bool spaceLocked_ = false;  // inside dSpaceCollide, or an error left it there
};

}  // namespace collide::ode
