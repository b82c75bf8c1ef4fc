#pragma once
// ODE's dCollideSpheres in binary32 or binary64 over structure-of-arrays (docs/scpu.md,
// "Semantics"), written branch-free so that GCC vectorizes it. Compiled with -ffp-contract=off:
// every operation is one correctly rounded RNE operation of the format, in the reference order.
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

// The whole batch: pair k's spheres i[k], j[k] gathered from a binary64 table (one RNE
// rounding to binary32, as the AFU's link does), the kernel above, and the binary32 results
// widened into binary64 outputs, block by block so everything stays in L1.
struct SpheresF64 {  // the sphere table
  const double *x, *y, *z, *r;
};
struct ContactsF64 {  // outputs, n entries each; zero where hit == 0
  double *px, *py, *pz, *nx, *ny, *nz, *depth;
  std::uint8_t* hit;
};
void gatherCollideF32(std::size_t n, const SpheresF64& s, const std::uint32_t* i, const std::uint32_t* j,
                      const ContactsF64& out);

// The same in binary64 throughout (the spheres as they are; the simd64 backend): what ODE's
// own dCollideSpheres computes, vectorized.
struct PairsF64 {  // inputs, n entries each
  const double *x1, *y1, *z1, *r1, *x2, *y2, *z2, *r2;
};
void collideSpheresF64(std::size_t n, const PairsF64& in, const ContactsF64& out);
void gatherCollideF64(std::size_t n, const SpheresF64& s, const std::uint32_t* i, const std::uint32_t* j,
                      const ContactsF64& out);

}  // namespace collide
