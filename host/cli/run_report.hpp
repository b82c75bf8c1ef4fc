#pragma once
// Totals of a scene run and the per-pair / per-collision CPU times reported by `run`.
#include <cstdint>
#include <ostream>

namespace collide::cli {

struct RunTotals {
  std::uint64_t pairs = 0, contacts = 0, otherContacts = 0;
  std::int64_t backendNs = 0, odeNs = 0, simdNs = 0;
  std::uint64_t hitMismatches = 0;  // pairs where ode and simd disagree on hit
};

// "X ms total, Y ns/pair, Z ns/collision" ("-" where a count is 0).
void printTiming(std::ostream& os, std::int64_t ns, std::uint64_t pairs, std::uint64_t contacts);

}  // namespace collide::cli
