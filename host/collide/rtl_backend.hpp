#pragma once
// `rtl` backend: the generated AFU (Verilated) behind the link model, through the driver.
// Construction fails with driver::AfuUnavailable when this build has no AFU.
// A batch larger than the AFU takes (afu.maxSpheres spheres, 2^24 - 1 pairs) is split into
// runs, each with the spheres its pairs use (in first-use order); empty batches make no run.
#include <filesystem>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "collide/backend.hpp"
#include "driver/afu_driver.hpp"
#include "driver/afu_factory.hpp"
#include "driver/wall_watchdog.hpp"
#include "link/link_params.hpp"

namespace collide {

// One backend call (a simulation step's batch), over every AFU run it took.
struct RtlBatchStats {
  std::size_t runs = 0;          // AFU calls: 1, more when the batch is split, 0 if empty
  driver::StatusLine counters;   // the status lines' counters summed over the runs
  driver::RunStats stats;        // cycles stepped/skipped, status cycles, modelled ns: sums

  // Sums `runs` AFU runs' status line and statistics into these totals (errors: OR).
  void add(const driver::StatusLine& s, const driver::RunStats& r, std::size_t n = 1);
  void add(const RtlBatchStats& b) { add(b.counters, b.stats, b.runs); }
};

// The link model can never finish a run sooner than driver::linkBoundNs allows; a modelled
// time below it means the model, the bound or the driver's protocol is broken, and every
// time reported from then on would be wrong. Throws std::logic_error ("internal error").
void requireAtLeastLinkBound(const driver::RunStats& run, const std::string& linkName);

class RtlBackend final : public CollisionBackend {
 public:
  RtlBackend(const std::filesystem::path& afuDir, const link::LinkParams& link,
             driver::DriverOptions options = {}, const driver::AfuPortOptions& portOptions = {});
  // For tests and other models: any AfuPort, owned by the backend.
  RtlBackend(std::unique_ptr<driver::AfuPort> port, const link::LinkParams& link,
             const driver::DriverOptions& options, double wallLimitS = driver::kDefaultWallLimitS);

  std::string name() const override { return "rtl"; }
  LinkFormat format() const override { return driver_->options().format; }
  void collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) override;
  bool setsRecordFlags() const override { return true; }

  // The last AFU run (of the last batch) and the last batch as a whole.
  const driver::RunResult& lastRun() const { return last_; }
  const RtlBatchStats& lastBatch() const { return batch_; }
  const driver::AfuDriver& driver() const { return *driver_; }

 private:
  void runOne(const SphereTable& spheres, const PairList& pairs, ContactSet& out);

  // Every port runs behind a wall-clock watchdog, armed at each run (driver/wall_watchdog.hpp).
  std::unique_ptr<driver::WallClockWatchdog> port_;
  std::unique_ptr<driver::AfuDriver> driver_;
  driver::RunResult last_;
  RtlBatchStats batch_;
  // Chunking scratch: global sphere -> chunk-local index, the chunk's table and pairs.
  std::vector<std::int32_t> local_;
  SphereTable chunkSpheres_;
  PairList chunkPairs_;
  std::vector<std::size_t> chunkOrigin_;
  ContactSet chunkOut_;
};

}  // namespace collide
