#include "collide/input_policy.hpp"

#include <cmath>

#include "afu_contract.hpp"
#include "batch/sane_ranges.hpp"
#include "collide/contact_flags.hpp"

namespace collide {

PairInput classifySphere(const SphereTable& s, std::uint32_t i) {
  const double v[4] = {s.x[i], s.y[i], s.z[i], s.r[i]};
  for (double x : v)
    if (!std::isfinite(x)) return PairInput::NonFinite;
  if (!limits::saneRadius(v[3]) || !limits::saneCoordinate(v[0]) || !limits::saneCoordinate(v[1]) || !limits::saneCoordinate(v[2]))
    return PairInput::OutOfRange;
  return PairInput::Ok;
}

PairInput classifyPair(const SphereTable& s, std::uint32_t i, std::uint32_t j) {
  const PairInput a = classifySphere(s, i), b = classifySphere(s, j);
  if (a == PairInput::NonFinite || b == PairInput::NonFinite) return PairInput::NonFinite;
  return a == PairInput::Ok ? b : a;
}

void applyInputPolicy(const SphereTable& s, const PairList& pairs, ContactSet& out) {
  out.flags.resize(pairs.size(), 0);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const PairInput p = classifyPair(s, pairs.i[k], pairs.j[k]);
    if (p == PairInput::Ok) continue;
    out.hit[k] = 0;
    out.px[k] = out.py[k] = out.pz[k] = out.nx[k] = out.ny[k] = out.nz[k] = out.depth[k] = 0;
    // The host's own range flag (the link format) survives; the backend's others do not.
    const std::uint8_t keep = out.flags[k] & contract::REC_HOST_RANGE;
    out.flags[k] = static_cast<std::uint8_t>(
        keep | (p == PairInput::NonFinite ? contract::REC_NONFINITE : contract::REC_HOST_RANGE));
  }
}

void collidePairs(CollisionBackend& backend, const SphereTable& s, const PairList& pairs, ContactSet& out) {
  backend.collide(s, pairs, out);
  finishPairs(backend, s, pairs, out);
}

void finishPairs(const CollisionBackend& backend, const SphereTable& s, const PairList& pairs, ContactSet& out) {
  if (!backend.setsRecordFlags()) setCpuRecordFlags(s, pairs, out.format, out);
  applyInputPolicy(s, pairs, out);
}

}  // namespace collide
