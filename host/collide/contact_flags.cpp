#include "collide/contact_flags.hpp"

#include <cmath>

#include "afu_contract.hpp"

namespace collide {

namespace {
template <typename T>
std::uint8_t flagsOf(bool hit, const T a[4], const T b[4]) {
  bool finite = true;
  for (int k = 0; k < 4; ++k) finite = finite && std::isfinite(a[k]) && std::isfinite(b[k]);
  std::uint32_t f = finite ? 0 : contract::REC_NONFINITE;
  if (hit) {
    const T dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    const T d2 = (dx * dx + dy * dy) + dz * dz;  // the SCPU's order, as the backends sum it
    f |= contract::REC_HIT | ((d2 == 0 ? contract::KIND_COINCIDENT : contract::KIND_CONTACT) << contract::REC_KIND_SHIFT);
  }
  return static_cast<std::uint8_t>(f);
}
}  // namespace

void setCpuRecordFlags(const SphereTable& s, const PairList& pairs, LinkFormat format, ContactSet& out) {
  out.flags.resize(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto i = pairs.i[k], j = pairs.j[k];
    const double a[4] = {s.x[i], s.y[i], s.z[i], s.r[i]}, b[4] = {s.x[j], s.y[j], s.z[j], s.r[j]};
    if (format == LinkFormat::Binary32) {
      float af[4], bf[4];
      for (int c = 0; c < 4; ++c) { af[c] = static_cast<float>(a[c]); bf[c] = static_cast<float>(b[c]); }
      out.flags[k] = flagsOf(out.hit[k] != 0, af, bf);
    } else {
      out.flags[k] = flagsOf(out.hit[k] != 0, a, b);
    }
  }
}

}  // namespace collide
