#include "ode/simulation.hpp"

#include <cmath>

#include "ode/contact_joints.hpp"

namespace collide::ode {

Simulation::Simulation(const scene::Scene& scene, CollisionBackend& backend)
    : scene_(scene), backend_(backend), world_(scene), surface_(surfaceFor(scene.contact)) {}

void Simulation::nearCallback(void* self, dGeomID o1, dGeomID o2) {
  static_cast<Simulation*>(self)->near(o1, o2);
}

void Simulation::near(dGeomID o1, dGeomID o2) {
  const long i = world_.sphereIndex(o1), j = world_.sphereIndex(o2);
  if (i >= 0 && j >= 0) {  // sphere/sphere: to the batch, o1 first (normal from o2 to o1)
    pairs_.push(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
    return;
  }
  // Anything else (sphere/plane) stays on the CPU through ODE's own colliders.
  dContactGeom cg[4];
  const int n = dCollide(o1, o2, 4, cg, sizeof(dContactGeom));
  for (int k = 0; k < n; ++k) addContactJoint(world_.world(), world_.contacts(), surface_, cg[k]);
  otherContacts_ += static_cast<std::size_t>(n);
}

void Simulation::applyEffects() {
  if (!scene_.attractor) return;  // gravity is the world's own setting
  const auto& a = *scene_.attractor;
  for (std::size_t k = 0; k < world_.sphereCount(); ++k) {
    dBodyID b = world_.sphereBody(k);
    const dReal* p = dBodyGetPosition(b);
    const double d[3] = {a.point[0] - p[0], a.point[1] - p[1], a.point[2] - p[2]};
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len > 0) dBodyAddForce(b, a.force * d[0] / len, a.force * d[1] / len, a.force * d[2] / len);
  }
}

StepStats Simulation::step() {
  StepStats st;
  st.step = step_;
  pairs_.clear();
  otherContacts_ = 0;
  applyEffects();
  dSpaceCollide(world_.space(), this, &Simulation::nearCallback);

  world_.fillSphereTable(table_);
  const auto t0 = std::chrono::steady_clock::now();
  backend_.collide(table_, pairs_, results_);
  st.backendNs = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count();
  if (observer_) observer_(table_, pairs_, results_);

  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    if (!results_.hit[k]) continue;
    dContactGeom g{};
    g.pos[0] = results_.px[k]; g.pos[1] = results_.py[k]; g.pos[2] = results_.pz[k];
    g.normal[0] = results_.nx[k]; g.normal[1] = results_.ny[k]; g.normal[2] = results_.nz[k];
    g.depth = results_.depth[k];
    g.g1 = world_.sphereGeom(pairs_.i[k]);
    g.g2 = world_.sphereGeom(pairs_.j[k]);
    g.side1 = g.side2 = -1;
    addContactJoint(world_.world(), world_.contacts(), surface_, g);
    ++st.contacts;
  }
  st.pairsTested = pairs_.size();
  st.otherContacts = otherContacts_;

  dWorldQuickStep(world_.world(), scene_.dt);
  dJointGroupEmpty(world_.contacts());
  ++step_;
  return st;
}

}  // namespace collide::ode
