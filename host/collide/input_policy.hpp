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
#include <cstdint>

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

// What `collide pairs` does with any backend: its results, the record flags (the CPU
// backends' computed as the AFU computes them), then the policy above.
void collidePairs(CollisionBackend& backend, const SphereTable& s, const PairList& pairs, ContactSet& out);
// The part after backend.collide (for callers that time the backend alone): flags, policy.
void finishPairs(const CollisionBackend& backend, const SphereTable& s, const PairList& pairs, ContactSet& out);

}  // namespace collide
