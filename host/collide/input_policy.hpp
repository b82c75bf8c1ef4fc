#pragma once
// What every backend does with a pair it cannot meaningfully collide (docs/host.md, "Bad
// pairs"): one rule, applied the same way to simd, ode and rtl results, so that the same bad
// input gives the same decision and the same flags whatever computed it.
//
// A pair is judged on its eight inputs as the backend received them (the table's values):
//  - non-finite: a NaN or an infinity among them -> no contact, REC_NONFINITE;
//  - out of range: a radius not in (0, 1e6] m or a centre coordinate beyond +-1e6 m (the range
//    ODE takes, batch/sane_ranges.hpp) -> no contact, REC_HOST_RANGE;
//  - else the backend's own result and flags.
// A rejected pair's fields are zero and its kind separated; ODE never sees it.
//
// Vector mode (`collide pairs`) has no hash space, so it computes every pair of finite values
// (collidePairs, below): a pair outside the range above is computed by the backend and only
// flagged REC_HOST_RANGE; a negative radius (ODE refuses it) is no contact with
// REC_HOST_RANGE; a non-finite value is no contact with REC_NONFINITE; a value that did not
// fit the backend's format (the reader's didNotFit) adds REC_HOST_RANGE.
#include <cstdint>
#include <vector>

#include "batch/batch.hpp"
#include "batch/contact_set.hpp"
#include "collide/backend.hpp"

namespace collide {

enum class PairInput { Ok, NonFinite, OutOfRange };

// One sphere's four values; a pair is NonFinite if either sphere is, else OutOfRange if either is.
PairInput classifySphere(const SphereTable& s, std::uint32_t i);
PairInput classifyPair(const SphereTable& s, std::uint32_t i, std::uint32_t j);

// Rewrites every rejected pair of `out` (which the backend filled) to no contact with its
// flag; keeps the flags the backend set on the others. out.flags is sized to the pairs.
void applyInputPolicy(const SphereTable& s, const PairList& pairs, ContactSet& out);

// The part after backend.collide (for callers that time the backend alone): the record
// flags (the CPU backends' computed as the AFU computes them), then the policy above.
void finishPairs(const CollisionBackend& backend, const SphereTable& s, const PairList& pairs, ContactSet& out);

// Vector mode's decision on one pair (the header's second paragraph).
enum class VectorInput {
  Ok,              // computed
  OutsideScene,    // computed, REC_HOST_RANGE: outside the range a scene takes
  NegativeRadius,  // no contact, REC_HOST_RANGE: no backend can take it (ODE asserts)
  NonFinite,       // no contact, REC_NONFINITE
};
VectorInput classifyVectorPair(const SphereTable& s, std::uint32_t i, std::uint32_t j);
// Whether a backend computes the pair at all (Ok or OutsideScene).
inline bool vectorComputes(VectorInput v) { return v == VectorInput::Ok || v == VectorInput::OutsideScene; }

// What `collide pairs` does with any backend: its results, the record flags, then vector
// mode's policy. didNotFit (per sphere, empty: none) marks a value the reader could not hold
// in the backend's format; every pair using that sphere gets REC_HOST_RANGE.
void collidePairs(CollisionBackend& backend, const SphereTable& s, const PairList& pairs, ContactSet& out,
                  const std::vector<std::uint8_t>& didNotFit = {});

}  // namespace collide
