#pragma once
// AAL-like driver for one AFU behind a link model: allocates the shared buffers in host
// memory, writes the sphere table and pair lines, configures and starts the AFU with CSR
// writes, clocks AFU + link until the status line says done (skipping idle cycles
// exactly), then reads and checks the contacts. See docs/host.md.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "batch/batch.hpp"
#include "batch/contact_set.hpp"
#include "driver/afu_layout.hpp"
#include "driver/afu_port.hpp"
#include "driver/contact_rebuild.hpp"
#include "driver/manifest.hpp"
#include "link/host_memory.hpp"
#include "link/link_model.hpp"

namespace collide::driver {

// The AFU misbehaved: hung (watchdog), raised error flags, or lost pairs/contacts.
struct AfuError : std::runtime_error {
  AfuError(const std::string& what, const StatusLine& s) : std::runtime_error(what), status(s) {}
  StatusLine status;
};

struct DriverOptions {
  LinkFormat format = LinkFormat::Binary32;  // the manifest's link.format
  std::uint32_t records = contract::LAYOUT_FULL;  // the manifest's buffers.records.layout
  ComputeArith arith;                        // the SCPU's arithmetic, to rebuild derived records
  bool dense = false;                        // MODE bit 0
  std::uint32_t maxSpheres = 65536;          // the manifest's afu.maxSpheres
  bool world = false;                        // the manifest's afu.world: runWorld is possible
  bool runQueue = false;                     // the manifest's afu.runQueue: runWorlds queues its runs
  // Cycles from the first CSR write to the status line before the run is declared hung.
  std::uint64_t watchdogCycles = 50'000'000;
  bool skipIdle = true;                      // jump the clock while the AFU idle-waits
  bool throwOnErrorFlags = true;             // any flag but "non-finite input seen"
};

// `o` with what the manifest fixes: link format, record layout, arithmetic, table size.
DriverOptions withManifest(DriverOptions o, const Manifest& m);

struct RunStats {
  std::uint64_t cyclesStepped = 0;   // cycles evaluated one by one
  std::uint64_t cyclesSkipped = 0;   // cycles jumped over while the AFU idle-waited
  std::uint64_t statusCycle = 0;     // cycles from the first CSR write to the status commit
  double modelledNs = 0;             // overhead + CSRs + AFU + poll detection
  std::uint64_t readLines = 0;       // lines the AFU read (sphere table + pair list)
  std::uint64_t writeLines = 0;      // lines the AFU wrote (contacts + status line)
  // The least time the link model allows for these lines (linkBoundNs below).
  double linkBoundNs = 0;
};

// Sums over several runs: every counter and statistic added (done counts the runs, errors
// OR-ed; the world cell exponent is the last run's).
void accumulate(StatusLine& into, const StatusLine& s);
void accumulate(RunStats& into, const RunStats& r);

// Lower bound the link model implies for a run that reads `readLines` and writes
// `writeLines` lines: the per-call costs it charges (transaction overhead, one CSR
// arrival, one poll), the shortest read and write round trips of the fastest channel (the
// first pair line cannot arrive sooner; the status line waits for the last contact's
// acknowledgement), and the busier direction's transfer at the channels' aggregate
// bandwidth, never faster than one line per cycle at the AFU port (less a correction for
// channels slower than any preset, see the .cpp). Latencies count in whole cycles, as
// the model draws them. It relies on run()'s protocol: nine CSR writes, no write before
// the first read's data, the status line last. docs/host.md.
double linkBoundNs(const link::LinkParams& lp, std::uint64_t readLines, std::uint64_t writeLines);

// Modelled host time of one call whose status line committed `statusCycle` cycles after
// the first CSR write: transaction overhead plus the poll that sees it.
double modelledRunNs(const link::LinkParams& lp, std::uint64_t statusCycle);

struct RunResult {
  StatusLine status;
  std::vector<ContactRecord> records;  // as written, in buffer order (derived ones rebuilt)
  // Pairs with an input that did not fit the link format (contract::REC_HOST_RANGE): the
  // AFU computed them on infinities or a zero radius, so their result is not the scene's.
  std::vector<std::uint32_t> rangePairs;
  RunStats stats;
};

// World mode (runWorld): the last run's result, its records naming their spheres (i < j,
// worldPairI/J of the pair field), in buffer order; stats summed over the runs it took.
struct WorldRunResult {
  RunResult run;
  // Runs it took: 1, or 2 when the first contact buffer was too small (the AFU counts every
  // contact even past the buffer's end, so the second run has room for all of them).
  std::size_t attempts = 0;
  // Spheres whose link-format values overflowed to infinity or whose radius rounded to zero
  // (the broad phase pairs no non-finite sphere; contacts of the others carry REC_HOST_RANGE).
  std::vector<std::uint32_t> rangeSpheres;
};

// World mode over several tables (runWorlds): each table's result, and the call's statistics.
struct WorldBatchResult {
  std::vector<WorldRunResult> runs;  // one per table, in order; with a queue, each run's stats
                                     // hold only its status cycle (the call's are in `stats`)
  RunStats stats;                    // the whole call: summed over the calls it took
  std::size_t calls = 0;             // driver calls (one per table without a queue; with one, 1
                                     // plus one per table whose contact buffer was too small)
};

// The CSR values of one run (docs/afu-interface.md).
struct RunCsrs {
  std::uint64_t sphereBase = 0, numSpheres = 0, pairBase = 0, numPairs = 0, contactBase = 0, capacity = 0,
                statusAddr = 0;
  std::uint32_t mode = 0;
};

std::string describeErrors(std::uint32_t flags);

class AfuDriver {
 public:
  AfuDriver(AfuPort& port, const link::LinkParams& link, const DriverOptions& options);

  RunResult run(const SphereTable& spheres, const PairList& pairs);
  // World mode: only the sphere table goes to the AFU; its broad phase finds the pairs.
  // `capacityHint`: contact records the first buffer holds (0: 8 per sphere, at least 64).
  // Throws std::invalid_argument if the AFU has no world mode or the table is too big.
  WorldRunResult runWorld(const SphereTable& spheres, std::size_t capacityHint = 0);
  // World mode on several tables. With the AFU's run queue (manifest afu.runQueue) in one
  // call: every table's run is started while the run before it is on, so its table loads
  // during that run's broad phase, and the call's costs are paid once; a run whose contact
  // buffer was too small is run again alone (runWorld), with room for all. Without a queue,
  // runWorld on each table. docs/host.md, "The run queue".
  WorldBatchResult runWorlds(const std::vector<SphereTable>& tables);

  // Dense per-pair view of a run's records (pair k -> entry k), in the link format, with the
  // record flags (and REC_HOST_RANGE on the run's rangePairs, whether or not they hit).
  ContactSet toContactSet(const RunResult& r, std::size_t pairs) const;
  BufferLayout layout() const { return BufferLayout{opt_.format, opt_.records}; }

  const link::LinkModel& link() const { return link_; }
  const DriverOptions& options() const { return opt_; }

 private:
  void check(const RunResult& r, std::size_t pairs, std::size_t capacity, std::size_t headers) const;
  void checkWorld(const RunResult& r, std::size_t spheres, std::size_t capacity) const;
  void execute(const RunCsrs& csrs, RunResult& r);
  void executeQueue(const std::vector<RunCsrs>& runs, std::vector<RunResult>& out, RunStats& stats);
  bool advance(std::uint64_t limit, RunStats& stats);
  static std::size_t worldCapacity(std::size_t spheres);  // a world run's first buffer: 8 a sphere, at least 64
  RunCsrs stageWorld(const SphereTable& spheres, std::size_t capacity, std::vector<std::uint8_t>& outOfRange);
  void postCsrs(const RunCsrs& c);
  [[noreturn]] void hung(std::uint64_t statusAddr) const;
  // Checks a world run's records and marks, rebuilds its derived records.
  void finishWorld(const SphereTable& spheres, const std::vector<std::uint8_t>& outOfRange, std::size_t capacity,
                   WorldRunResult& w) const;
  void rebuildDerived(const SphereTable& spheres, RunResult& r, const PairList* pairs) const;

  AfuPort& port_;
  DriverOptions opt_;
  link::HostMemory mem_;
  link::LinkModel link_;
};

}  // namespace collide::driver
