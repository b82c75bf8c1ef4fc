#pragma once
// ODE's dCollideSpheres in binary32 over structure-of-arrays (ARCHITECTURE.md), written
// branch-free so that GCC vectorizes it. Compiled with -ffp-contract=off: every operation
// is one correctly rounded binary32 RNE operation, in the reference order.
#include <cstddef>
#include <cstdint>

namespace collide {

struct PairsF32 {  // inputs, n entries each
  const float *x1, *y1, *z1, *r1, *x2, *y2, *z2, *r2;
};
struct ContactsF32 {  // outputs, n entries each; zero where hit == 0
  float *px, *py, *pz, *nx, *ny, *nz, *depth;
  std::uint8_t* hit;
};

void collideSpheresF32(std::size_t n, const PairsF32& in, const ContactsF32& out);

}  // namespace collide
