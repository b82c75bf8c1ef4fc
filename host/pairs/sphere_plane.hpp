#pragma once
// Sphere/plane, ODE 0.16's dCollideSpherePlane (ode/src/sphere.cpp) operation for operation in
// T = float (the AFU's binary32 unit, collide.pairs.SpherePlane) or T = double (ODE's own
// arithmetic): with the project's -ffp-contract=off both are IEEE operations in ODE's order, so
// the double form equals dCollide bit for bit and the float form equals the Scala golden model
// (collide.pairs.model.SpherePlaneModel) in binary32 (test/test_pair_kinds.cpp checks both).
// docs/pair-kinds.md describes the kind, its order of operations and its error bound.

#include "pairs/contact.hpp"

namespace collide::pairs {

template <typename T>
using SpherePlaneContact = Contact<T>;

// c: the sphere's centre, r its radius; plane: (nx, ny, nz, d) as dGeomPlaneGetParams gives it
// (a unit normal; the plane is n . x = d). One contact, or none (hit false, every field 0).
template <typename T>
SpherePlaneContact<T> collideSpherePlane(const T c[3], T r, const T plane[4]) {
  SpherePlaneContact<T> out;
  const T k = c[0] * plane[0] + c[1] * plane[1] + c[2] * plane[2];  // dCalcVectorDot3
  const T depth = plane[3] - k + r;
  if (!(depth >= 0)) return out;  // a NaN depth is no contact, as in ODE
  out.hit = true;
  for (int i = 0; i < 3; ++i) {
    out.normal[i] = plane[i];
    out.pos[i] = c[i] - plane[i] * r;
  }
  out.depth = depth;
  return out;
}

}  // namespace collide::pairs
