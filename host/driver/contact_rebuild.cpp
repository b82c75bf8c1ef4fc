#include "driver/contact_rebuild.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "afu_contract.hpp"
#include "scpu/scpu_model.hpp"

namespace collide::driver {

void rebuildContact(const ComputeArith& a, const double s1[4], const double s2[4], double d, double w,
                    std::uint8_t flags, double out[7]) {
  std::fill(out, out + 7, 0.0);
  if (!(flags & contract::REC_HIT)) return;
  scpu::RoundedArith c(a.compute);
  // link -> compute (the SCPU's input conversion; the identity when the formats agree)
  double p1[4], p2[4];
  for (int k = 0; k < 4; ++k) { p1[k] = c.round(s1[k]); p2[k] = c.round(s2[k]); }
  const double rs = c.add(p1[3], p2[3]);
  const unsigned kind = (flags >> contract::REC_KIND_SHIFT) & contract::REC_KIND_MASK;
  if (kind == contract::KIND_COINCIDENT) {
    out[0] = p1[0]; out[1] = p1[1]; out[2] = p1[2];
    out[3] = 1.0; out[6] = rs;
    return;
  }
  if (kind != contract::KIND_CONTACT) return;
  double u[3] = {c.sub(p1[0], p2[0]), c.sub(p1[1], p2[1]), c.sub(p1[2], p2[2])};
  if (a.distance == DistanceMethod::Robust) {
    const int e = scpu::scaleExponent(u);
    for (double& x : u) x = c.scale(x, -e);
  }
  scpu::contactPath(c, p1, p2, u, rs, d, w, out);
}

}  // namespace collide::driver
