#include "world/afu_world.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "collide/input_policy.hpp"
#include "collide/rtl_backend.hpp"
#include "world/slab_split.hpp"

namespace collide::world {

namespace {
driver::DriverOptions fromManifest(const std::filesystem::path& dir, const driver::DriverOptions& base) {
  const auto m = driver::afuManifest(dir);
  if (!m.world)
    throw driver::AfuUnavailable("AFU " + (dir.empty() ? std::string("built in") : dir.string()) +
                                ": no world mode (manifest afu.world is not true; generate the world preset: "
                                "tools/sbt \"run --preset world\")");
  return driver::withManifest(base, m);
}
}  // namespace

AfuWorld::AfuWorld(const std::filesystem::path& afuDir, const link::LinkParams& link,
                   const driver::AfuPortOptions& portOptions, const driver::DriverOptions& base)
    : port_(std::make_unique<driver::WallClockWatchdog>(driver::makeAfuPort(afuDir, portOptions),  // AfuUnavailable first
                                                        portOptions.wallLimitS)) {
  driver_ = std::make_unique<driver::AfuDriver>(*port_, link, fromManifest(afuDir, base));
}

AfuWorld::AfuWorld(std::unique_ptr<driver::AfuPort> port, const link::LinkParams& link,
                   const driver::DriverOptions& options, double wallLimitS)
    : port_(std::make_unique<driver::WallClockWatchdog>(std::move(port), wallLimitS)),
      driver_(std::make_unique<driver::AfuDriver>(*port_, link, options)) {}

void AfuWorld::collide(const SphereTable& s, WorldContacts& out) {
  out = WorldContacts{};
  const LinkFormat fmt = driver_->options().format;
  out.contacts.format = fmt;
  splitSpheres(s, out, members_);

  // One run, or slabs along x or boxes along x and y, whichever cut has the fewest spheres in
  // all (ghosts included; a run counts for cap / 16 more), by the values the AFU sees.
  const std::size_t cap = maxRun_ ? std::min<std::size_t>(maxRun_, driver_->options().maxSpheres)
                                  : driver_->options().maxSpheres;
  std::vector<Slab> slabs;
  if (members_.size() <= cap) {
    Slab all;
    for (std::uint32_t k = 0; k < members_.size(); ++k) { all.spheres.push_back(k); all.owned.push_back(kOwnedBoth); }
    all.ownedCount = members_.size();
    slabs.push_back(std::move(all));
  } else {
    std::vector<double> x(members_.size()), y(members_.size()), r(members_.size());
    for (std::size_t k = 0; k < members_.size(); ++k) {
      double q[4];
      driver::linkSphere(s, members_[k], fmt, q);
      x[k] = q[0];
      y[k] = q[1];
      r[k] = q[3];
    }
    slabs = splitIntoRuns(x, y, r, cap);
  }

  last_ = driver::WorldRunResult{};
  slabs_ = slabs.size();
  tables_.resize(slabs.size());
  for (std::size_t k = 0; k < slabs.size(); ++k) {
    tables_[k].clear();
    for (auto p : slabs[k].spheres) {
      const auto m = members_[p];
      tables_[k].push(s.x[m], s.y[m], s.z[m], s.r[m]);
    }
  }
  // One call for every slab where the AFU queues runs (each table loading during the run
  // before it), else a call a slab; the wall-clock limit is the call's.
  port_->arm();
  const driver::WorldBatchResult batch = driver_->runWorlds(tables_);
  requireAtLeastLinkBound(batch.stats, driver_->link().params().name);
  last_.run.stats = batch.stats;
  calls_ = batch.calls;
  PairList pairs;
  ContactSet found;
  found.format = fmt;
  std::vector<std::uint32_t> range;
  runs_.clear();
  for (std::size_t k = 0; k < slabs.size(); ++k) {
    const Slab& slab = slabs[k];
    const driver::WorldRunResult& r = batch.runs[k];
    runs_.push_back({slab.spheres.size(), r.attempts, r.run.status});
    driver::accumulate(last_.run.status, r.run.status);
    last_.attempts += r.attempts;
    // Records name table rows; a run's table is ascending in the caller's indices, so i < j
    // stays i < j. A pair is this run's when keepsPair says so (owned here along x and y).
    for (const auto& rec : r.run.records) {
      const auto li = driver::worldPairI(rec.pair), lj = driver::worldPairJ(rec.pair);
      if (!keepsPair(slab, li, lj)) continue;
      const std::size_t i = pairs.size();
      pairs.push(members_[slab.spheres[li]], members_[slab.spheres[lj]]);
      found.resizeForOverwrite(i + 1);
      found.hit[i] = 1;
      found.px[i] = rec.px; found.py[i] = rec.py; found.pz[i] = rec.pz;
      found.nx[i] = rec.nx; found.ny[i] = rec.ny; found.nz[i] = rec.nz;
      found.depth[i] = rec.depth;
      found.flags[i] = rec.flags;
    }
    for (auto m : r.rangeSpheres) range.push_back(members_[slab.spheres[m]]);
  }
  out.candidates = last_.run.status.pairsProcessed;
  out.flaggedMisses = last_.run.status.flaggedMisses;
  // A sphere whose link value overflowed is non-finite to the AFU, which pairs it with
  // nothing: it is listed as bad (once, though several runs held it), like a sphere the
  // policy rejects.
  if (!range.empty()) {
    std::sort(range.begin(), range.end());
    range.erase(std::unique(range.begin(), range.end()), range.end());
    last_.rangeSpheres = range;
    std::vector<std::pair<std::uint32_t, std::uint8_t>> bad;
    for (std::size_t k = 0; k < out.badSpheres.size(); ++k) bad.emplace_back(out.badSpheres[k], out.badFlags[k]);
    for (auto k : range) bad.emplace_back(k, contract::REC_HOST_RANGE);
    std::sort(bad.begin(), bad.end());
    out.badSpheres.clear(); out.badFlags.clear();
    for (const auto& [k, f] : bad) { out.badSpheres.push_back(k); out.badFlags.push_back(f); }
  }
  applyInputPolicy(s, pairs, found);
  keepSortedHits(pairs, found, out);
}

void AfuWorld::collide(const SphereTable& s, WorldContacts& out, WorldTiming& time) {
  collide(s, out);
  const double broad = last_.run.status.cyclesBroad * cycleNs();
  time = WorldTiming{};
  time.broadNs = static_cast<std::int64_t>(broad + 0.5);
  time.narrowNs = static_cast<std::int64_t>(last_.run.stats.modelledNs - broad + 0.5);
}

}  // namespace collide::world
