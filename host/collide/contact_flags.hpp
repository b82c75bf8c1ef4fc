#pragma once
// The record flags (docs/afu-interface.md, contract::REC_*) for a CPU backend's results,
// computed the way the AFU computes them: hit, the kind (coincident when d = 0, which in
// the backend's own format means d^2 = (dx*dx + dy*dy) + dz*dz = 0) and non-finite input.
// The CPU backends do not observe the arithmetic's exceptions, so REC_ARITH stays clear.
#include "batch/batch.hpp"
#include "batch/contact_set.hpp"

namespace collide {

// Fills out.flags from out.hit and the pairs' inputs rounded to `format`.
void setCpuRecordFlags(const SphereTable& s, const PairList& pairs, LinkFormat format, ContactSet& out);

}  // namespace collide
