#pragma once
// The host side of the AFU's derived record layout (docs/afu-interface.md, "Contacts"):
// the AFU sends only d and w (the results of the square root and the reciprocal), and the
// host rebuilds position, normal and depth from its own sphere table with the SCPU's
// operations in the SCPU's order and format, so the contact is bit for bit the one a full
// record would carry. Exact when the compute format rounds to nearest even with subnormals
// kept and is binary64 or at most 25 significand bits (one binary64 operation then one
// rounding equals the format's own operation: the 2p+2 rule); the generator refuses the
// layout elsewhere, and so does the manifest reader.
#include <cstdint>

#include "scpu/scpu_arith.hpp"

namespace collide::driver {

using scpu::ComputeArith;
using scpu::DistanceMethod;

// s1, s2: x, y, z, r of spheres i and j as the link carries them. d, w: the record's values
// (link format). flags: the record's flags byte. out: px, py, pz, nx, ny, nz, depth in the
// link format, as the full record of the same pair would hold them (zeros unless a hit).
void rebuildContact(const ComputeArith& a, const double s1[4], const double s2[4], double d, double w,
                    std::uint8_t flags, double out[7]);

}  // namespace collide::driver
