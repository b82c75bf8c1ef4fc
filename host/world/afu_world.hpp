#pragma once
// World mode on the AFU (docs/host.md, "collide spheres"): the spheres the input policy
// takes go to the AFU as one table; its on-chip broad phase finds the candidate pairs, its
// SCPUs the contacts, and each record names its two spheres. The result is the CPU world
// collider's: the same bad-sphere list, contacts sorted by (i, j), the policy's flags.
// A world larger than the AFU's table is cut into slabs along x, or boxes along x and y
// (world/slab_split.hpp), one AFU run each, every pair found in exactly one of them.
#include <filesystem>
#include <memory>
#include <vector>

#include "driver/afu_driver.hpp"
#include "driver/afu_factory.hpp"
#include "driver/wall_watchdog.hpp"
#include "link/link_params.hpp"
#include "world/world_collider.hpp"
#include "world/world_engine.hpp"

namespace collide::world {

class AfuWorld final : public WorldEngine {
 public:
  // The AFU of `afuDir` (empty: the one built in); throws driver::AfuUnavailable when this
  // build has none or its manifest has no world mode. `base`: the driver options the
  // manifest does not fix (skipIdle, watchdog).
  AfuWorld(const std::filesystem::path& afuDir, const link::LinkParams& link,
           const driver::AfuPortOptions& portOptions = {}, const driver::DriverOptions& base = {});
  // Any port (tests), with the driver options its manifest would give.
  AfuWorld(std::unique_ptr<driver::AfuPort> port, const link::LinkParams& link, const driver::DriverOptions& options,
           double wallLimitS = driver::kDefaultWallLimitS);

  void collide(const SphereTable& s, WorldContacts& out);
  // WorldEngine: time modelled, broadNs the broad phase's cycles, narrowNs the rest of the call.
  std::string name() const override { return "rtl (the AFU's world mode)"; }
  void collide(const SphereTable& s, WorldContacts& out, WorldTiming& time) override;
  bool modelled() const override { return true; }
  // The last call: status counters and statistics summed over its runs (candidates and
  // contacts of ghost pairs included), attempts summed; records are not kept.
  const driver::WorldRunResult& lastRun() const { return last_; }
  // AFU runs (slabs) the last call took.
  std::size_t lastSlabs() const { return slabs_; }
  // One run of the last call: the spheres its table held (ghosts included), the attempts it
  // took and its own status line (the last attempt's), so a caller sees each run's cycles.
  struct RunSummary {
    std::size_t spheres = 0, attempts = 0;
    driver::StatusLine status;
  };
  const std::vector<RunSummary>& lastRuns() const { return runs_; }
  // Driver calls the last call took: 1 with a run queue (plus one a run whose contact buffer
  // was too small), else one a slab (and a second for such a run).
  std::size_t lastCalls() const { return calls_; }
  // Spheres a run may hold (0: the AFU's afu.maxSpheres); smaller values cut worlds sooner.
  void setMaxRunSpheres(std::size_t n) { maxRun_ = n; }
  const driver::AfuDriver& driver() const { return *driver_; }
  // Cycle period of the link model, to turn the status line's cycles into time.
  double cycleNs() const { return driver_->link().params().cycleNs(); }

 private:
  std::unique_ptr<driver::WallClockWatchdog> port_;
  std::unique_ptr<driver::AfuDriver> driver_;
  driver::WorldRunResult last_;
  std::size_t slabs_ = 0, maxRun_ = 0, calls_ = 0;
  std::vector<std::uint32_t> members_;
  std::vector<SphereTable> tables_;
  std::vector<RunSummary> runs_;
};

}  // namespace collide::world
