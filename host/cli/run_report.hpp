#pragma once
// Totals of a scene run and the per-pair / per-collision CPU times reported by `run`.
#include <cstdint>
#include <ostream>
#include <string>

#include "collide/rtl_backend.hpp"

namespace collide::cli {

struct RunTotals {
  std::uint64_t pairs = 0, contacts = 0, otherPairs = 0, otherContacts = 0;
  std::int64_t backendNs = 0, odeNs = 0, simdNs = 0, simd64Ns = 0;
  std::uint64_t hitMismatches = 0;    // pairs where ode and simd disagree on hit
  std::uint64_t hit64Mismatches = 0;  // the same for simd64 (0 unless its arithmetic left ODE's)
  // The steps' time split (sim::StepStats): broad phase, sphere/plane narrow phase, contact
  // joints, solver, and the whole steps (the sphere/sphere narrow phase is backendNs).
  std::int64_t broadNs = 0, otherNarrowNs = 0, jointsNs = 0, solverNs = 0, stepNs = 0;
  // Offload "world": the engine's own broad / rest split (sim::StepStats::worldBroadNs...).
  std::int64_t worldBroadNs = 0, worldNarrowNs = 0;
  // The physics (sim::StepStats): the largest kinetic energy, deepest contact and escaped count
  // over the steps, and the last step's kinetic energy.
  double maxKineticJ = 0, lastKineticJ = 0, maxDepthM = 0;
  std::size_t maxEscaped = 0;
};

// Where a run's step time went, one line per stage with its share. `narrowNs` is the
// sphere/sphere narrow phase as the run should count it: the backend's wall time on the CPU
// backends, the modelled AFU time on rtl (its co-simulation's wall time is no real cost), so
// the total is the steps' wall time with the backend's wall replaced by narrowNs.
// A world engine (offload "world") does the broad phase inside that call: `engineBroadNs` is
// its own account of it (measured, or modelled on the AFU), added to the broad-phase line.
void printTimeSplit(std::ostream& os, const RunTotals& t, double narrowNs, const std::string& narrowWhat,
                    long long steps, double engineBroadNs, const std::string& broadWhat);

// The rtl backend's modelled AFU time over a run (sums over every AFU call), split as the
// paper's Figures 5-7: the status line's cycle counters, and what lies outside them.
struct AfuTotals : RtlBatchStats {
  double cycleNs = 5.0;
  // AFU cycles that none of the counters claims (they may overlap: then negative; world mode's
  // broad phase overlaps the SCPUs' computing in its last pass).
  double otherNs() const {
    const auto& c = counters;
    return (static_cast<double>(c.cyclesTotal) - static_cast<double>(c.cyclesLoading + c.cyclesComputing + c.cyclesWaitRead +
                                                                     c.cyclesWaitWrite + c.cyclesBroad)) * cycleNs;
  }
  // Modelled time outside the AFU's own cycle count.
  double overheadNs() const { return stats.modelledNs - static_cast<double>(counters.cyclesTotal) * cycleNs; }
};

// "X ms total, Y ns/pair, Z ns/collision" ("-" where a count is 0).
void printTiming(std::ostream& os, std::int64_t ns, std::uint64_t pairs, std::uint64_t contacts);

}  // namespace collide::cli
