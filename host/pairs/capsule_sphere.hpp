#pragma once
// Capsule/sphere, ODE 0.16's dCollideCapsuleSphere (ode/src/capsule.cpp) operation for operation
// in T = float (the AFU's binary32 unit, collide.pairs.CapsuleSphere) or T = double (ODE's own
// arithmetic): the point of the capsule's axis nearest the sphere, then ODE's dCollideSpheres
// on it through the simd kernel (collide/simd_kernel.hpp, the sphere SCPU's arithmetic).
// test/test_pair_kinds.cpp checks the double form against dCollide and both against the
// Scala golden model's vectors; docs/pair-kinds.md describes the kind and its bound.
#include <cmath>
#include <cstdint>

#include "collide/simd_kernel.hpp"
#include "pairs/contact.hpp"

namespace collide::pairs {

namespace detail {
inline void collideSpheres(const float p[3], float r1, const float s[3], float r2, Contact<float>& out) {
  std::uint8_t hit = 0;
  collideSpheresF32(1, PairsF32{&p[0], &p[1], &p[2], &r1, &s[0], &s[1], &s[2], &r2},
                    ContactsF32{&out.pos[0], &out.pos[1], &out.pos[2], &out.normal[0], &out.normal[1], &out.normal[2],
                                &out.depth, &hit});
  out.hit = hit != 0;
}
inline void collideSpheres(const double p[3], double r1, const double s[3], double r2, Contact<double>& out) {
  std::uint8_t hit = 0;
  collideSpheresF64(1, PairsF64{&p[0], &p[1], &p[2], &r1, &s[0], &s[1], &s[2], &r2},
                    ContactsF64{&out.pos[0], &out.pos[1], &out.pos[2], &out.normal[0], &out.normal[1], &out.normal[2],
                                &out.depth, &hit});
  out.hit = hit != 0;
}
}  // namespace detail

// c: the capsule's centre; axis: its rotation's third column (R[2], R[6], R[10]), a unit vector
// as ODE keeps it; lz: the length of its cylinder part (dCreateCapsule's); rc: its radius;
// s, rs: the sphere. One contact (a sphere contact between the axis point and the sphere) or none.
template <typename T>
Contact<T> collideCapsuleSphere(const T c[3], const T axis[3], T lz, T rc, const T s[3], T rs) {
  T alpha = axis[0] * (s[0] - c[0]) + axis[1] * (s[1] - c[1]) + axis[2] * (s[2] - c[2]);
  const T lz2 = lz * T(0.5);
  if (alpha > lz2) alpha = lz2;
  if (alpha < -lz2) alpha = -lz2;
  T p[3];
  for (int i = 0; i < 3; ++i) p[i] = c[i] + alpha * axis[i];
  Contact<T> out;
  // A NaN distance is no contact, as in the SCPU (docs/scpu.md): ODE's `d > r1 + r2` lets it
  // through. The distance is NaN exactly when a difference p - s is.
  for (int i = 0; i < 3; ++i)
    if (std::isnan(p[i] - s[i])) return out;
  detail::collideSpheres(p, rc, s, rs, out);
  return out;
}

}  // namespace collide::pairs
