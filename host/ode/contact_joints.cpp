#include "ode/contact_joints.hpp"

#include <cmath>

namespace collide::ode {

dSurfaceParameters surfaceFor(const scene::ContactModel& m) {
  dSurfaceParameters s{};
  s.mu = std::isinf(m.mu) ? dInfinity : m.mu;
  if (m.bounce) {
    s.mode |= dContactBounce;
    s.bounce = *m.bounce;
    s.bounce_vel = m.bounceVel.value_or(0.0);
  }
  if (m.softCfm) {
    s.mode |= dContactSoftCFM;
    s.soft_cfm = *m.softCfm;
  }
  if (m.coulomb) s.mode |= dContactApprox1;  // Coulomb's law: the limit scales with the normal force
  return s;
}

void addContactJoint(dWorldID world, dJointGroupID group, const dSurfaceParameters& surface,
                     const dContactGeom& geom) {
  dContact c{};
  c.surface = surface;
  c.geom = geom;
  dJointID j = dJointCreateContact(world, group, &c);
  dJointAttach(j, dGeomGetBody(geom.g1), dGeomGetBody(geom.g2));
}

}  // namespace collide::ode
