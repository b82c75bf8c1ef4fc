#include "collide/input_policy.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "afu_contract.hpp"
#include "batch/sane_ranges.hpp"
#include "collide/contact_flags.hpp"

namespace collide {

namespace {
// Pair k becomes no contact with fields zero and flags `flag`; the host's own range flag
// (a value outside the link format) survives, the backend's other flags do not.
void rejectPair(ContactSet& out, std::size_t k, std::uint32_t flag) {
  out.hit[k] = 0;
  out.px[k] = out.py[k] = out.pz[k] = out.nx[k] = out.ny[k] = out.nz[k] = out.depth[k] = 0;
  out.flags[k] = static_cast<std::uint8_t>((out.flags[k] & contract::REC_HOST_RANGE) | flag);
}

// The record flags: the AFU's own, or the CPU backends' computed as the AFU computes them.
void setRecordFlags(const CollisionBackend& backend, const SphereTable& s, const PairList& pairs, ContactSet& out) {
  if (!backend.setsRecordFlags()) setCpuRecordFlags(s, pairs, out.format, out);
  out.flags.resize(pairs.size(), 0);
}
}  // namespace

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
    rejectPair(out, k, p == PairInput::NonFinite ? contract::REC_NONFINITE : contract::REC_HOST_RANGE);
  }
}

VectorInput classifyVectorPair(const SphereTable& s, std::uint32_t i, std::uint32_t j) {
  const PairInput p = classifyPair(s, i, j);
  if (p == PairInput::NonFinite) return VectorInput::NonFinite;
  if (p == PairInput::Ok) return VectorInput::Ok;
  // -0.0 < 0 is false: a zero radius, which ODE takes.
  if (s.r[i] < 0 || s.r[j] < 0) return VectorInput::NegativeRadius;
  return VectorInput::OutsideScene;
}

void collidePairs(CollisionBackend& backend, const SphereTable& s, const PairList& pairs, ContactSet& out,
                  const std::vector<std::uint8_t>& didNotFit) {
  if (!didNotFit.empty() && didNotFit.size() != s.size())
    throw std::logic_error("collidePairs: didNotFit has " + std::to_string(didNotFit.size()) + " entries for " +
                           std::to_string(s.size()) + " spheres");
  backend.collide(s, pairs, out);
  setRecordFlags(backend, s, pairs, out);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto i = pairs.i[k], j = pairs.j[k];
    const VectorInput v = classifyVectorPair(s, i, j);
    if (v == VectorInput::NonFinite) rejectPair(out, k, contract::REC_NONFINITE);
    if (v == VectorInput::NegativeRadius) rejectPair(out, k, contract::REC_HOST_RANGE);
    const bool unfit = !didNotFit.empty() && (didNotFit[i] || didNotFit[j]);
    if (unfit || v == VectorInput::OutsideScene) out.flags[k] |= contract::REC_HOST_RANGE;
  }
}

void finishPairs(const CollisionBackend& backend, const SphereTable& s, const PairList& pairs, ContactSet& out) {
  setRecordFlags(backend, s, pairs, out);
  applyInputPolicy(s, pairs, out);
}

}  // namespace collide
