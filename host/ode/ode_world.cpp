#include "ode/ode_world.hpp"

#include <cstdint>
#include <stdexcept>

#include "ode/hash_space_repair.hpp"

namespace collide::ode {

dSpaceID createSpace(limits::OdeSpaceKind kind) {
  switch (kind) {
    case limits::OdeSpaceKind::SweepAndPrune: return dSweepAndPruneSpaceCreate(nullptr, dSAP_AXES_XYZ);
    case limits::OdeSpaceKind::Hash: return dHashSpaceCreate(nullptr);
    case limits::OdeSpaceKind::QuadTree: break;
  }
  throw std::logic_error("ode::createSpace: a quadtree space needs its world's box (world/ode_space_broad_phase.*)");
}

World::World(const scene::Scene& s)
    : world_(dWorldCreate()), space_(createSpace(s.space)), contacts_(dJointGroupCreate(0)) {
  // Only what the scene declares: ODE's defaults otherwise (gravity 0 by default).
  if (s.gravity) dWorldSetGravity(world_, (*s.gravity)[0], (*s.gravity)[1], (*s.gravity)[2]);
  else dWorldSetGravity(world_, 0, 0, 0);
  if (s.worldCfm) dWorldSetCFM(world_, *s.worldCfm);
  if (s.worldErp) dWorldSetERP(world_, *s.worldErp);
  if (s.quickStepIterations) dWorldSetQuickStepNumIterations(world_, *s.quickStepIterations);
  if (s.maxCorrectingVel) dWorldSetContactMaxCorrectingVel(world_, *s.maxCorrectingVel);
  if (s.surfaceLayer) dWorldSetContactSurfaceLayer(world_, *s.surfaceLayer);

  bodies_.reserve(s.spheres.size());
  geoms_.reserve(s.spheres.size());
  for (std::size_t k = 0; k < s.spheres.size(); ++k) {
    const auto& sp = s.spheres[k];
    dBodyID b = dBodyCreate(world_);
    dMass m;
    dMassSetSphereTotal(&m, sp.mass, sp.radius);
    dBodySetMass(b, &m);
    dBodySetPosition(b, sp.pos[0], sp.pos[1], sp.pos[2]);
    dBodySetLinearVel(b, sp.vel[0], sp.vel[1], sp.vel[2]);
    dGeomID g = dCreateSphere(space_, sp.radius);
    dGeomSetBody(g, b);
    // The sphere index travels with the geom, for the near callback.
    dGeomSetData(g, reinterpret_cast<void*>(static_cast<std::uintptr_t>(k + 1)));
    bodies_.push_back(b);
    geoms_.push_back(g);
  }
  // Planes have null data: not spheres, so their pairs stay on the CPU (dCollide).
  if (s.groundZ) dCreatePlane(space_, 0, 0, 1, *s.groundZ);
  for (const auto& p : s.planes) dCreatePlane(space_, p.normal[0], p.normal[1], p.normal[2], p.offset);
}

World::~World() {
  dJointGroupDestroy(contacts_);
  // An ODE error inside dSpaceCollide (ode_errors.hpp) unwinds with the space still locked,
  // and ODE refuses to destroy a locked space or the bodies of its geoms: then both are
  // left to the process's end, so that the first error is the one reported.
  if (spaceLocked_) return;
  dSpaceDestroy(space_);  // destroys the geoms it holds (cleanup mode on by default)
  dWorldDestroy(world_);  // destroys the bodies
}

void World::collideSpace(void* data, dNearCallback* callback) {
  spaceLocked_ = true;  // stays set if an ODE error unwinds out of dSpaceCollide
  ode::collideSpace(space_, data, callback);  // dSpaceCollide, with the pairs ODE's hash space drops
  spaceLocked_ = false;
}

long World::sphereIndex(dGeomID g) const {
  return static_cast<long>(reinterpret_cast<std::uintptr_t>(dGeomGetData(g))) - 1;
}

void World::fillSphereTable(SphereTable& t) const {
  t.clear();
  for (std::size_t k = 0; k < geoms_.size(); ++k) {
    const dReal* p = dBodyGetPosition(bodies_[k]);
    t.push(p[0], p[1], p[2], dGeomSphereGetRadius(geoms_[k]));
  }
}

}  // namespace collide::ode
