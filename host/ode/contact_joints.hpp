#pragma once
// Contacts -> ODE contact joints with the scene's contact model.
#include <ode/ode.h>

#include "scene/scene.hpp"

namespace collide::ode {

// ODE surface parameters for a contact model: a mode bit only for what is declared.
dSurfaceParameters surfaceFor(const scene::ContactModel& m);

// One contact joint between the bodies of g1 and g2 (either may be static: no body).
// The normal must point from g2 to g1, ODE's convention for dCollide(g1, g2).
void addContactJoint(dWorldID world, dJointGroupID group, const dSurfaceParameters& surface,
                     const dContactGeom& geom);

}  // namespace collide::ode
