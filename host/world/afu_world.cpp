#include "world/afu_world.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "collide/input_policy.hpp"
#include "collide/rtl_backend.hpp"
#include "driver/manifest.hpp"

namespace collide::world {

namespace {
driver::DriverOptions fromManifest(const std::filesystem::path& dir) {
  const auto m = dir.empty() ? driver::parseManifest(driver::builtInAfuManifest(), "the built-in AFU's manifest")
                             : driver::loadManifest(dir);
  if (!m.world)
    throw driver::AfuUnavailable("AFU " + (dir.empty() ? std::string("built in") : dir.string()) +
                                ": no world mode (manifest afu.world is not true; generate the world preset: "
                                "tools/sbt \"run --preset world\")");
  return driver::withManifest(driver::DriverOptions{}, m);
}
}  // namespace

AfuWorld::AfuWorld(const std::filesystem::path& afuDir, const link::LinkParams& link,
                   const driver::AfuPortOptions& portOptions)
    : port_(std::make_unique<driver::WallClockWatchdog>(driver::makeAfuPort(afuDir, portOptions),  // AfuUnavailable first
                                                        portOptions.wallLimitS)) {
  driver_ = std::make_unique<driver::AfuDriver>(*port_, link, fromManifest(afuDir));
}

AfuWorld::AfuWorld(std::unique_ptr<driver::AfuPort> port, const link::LinkParams& link,
                   const driver::DriverOptions& options, double wallLimitS)
    : port_(std::make_unique<driver::WallClockWatchdog>(std::move(port), wallLimitS)),
      driver_(std::make_unique<driver::AfuDriver>(*port_, link, options)) {}

void AfuWorld::collide(const SphereTable& s, WorldContacts& out) {
  out = WorldContacts{};
  out.contacts.format = driver_->options().format;
  splitSpheres(s, out, members_);
  table_.clear();
  for (auto k : members_) table_.push(s.x[k], s.y[k], s.z[k], s.r[k]);

  port_->arm();
  last_ = driver_->runWorld(table_);
  requireAtLeastLinkBound(last_.run.stats, driver_->link().params().name);
  out.candidates = last_.run.status.pairsProcessed;

  // Records name table rows: back to the caller's indices (members_ ascending keeps i < j).
  PairList pairs;
  ContactSet found;
  found.format = out.contacts.format;
  found.resize(last_.run.records.size());
  for (std::size_t k = 0; k < last_.run.records.size(); ++k) {
    const auto& rec = last_.run.records[k];
    pairs.push(members_[driver::worldPairI(rec.pair)], members_[driver::worldPairJ(rec.pair)]);
    found.hit[k] = 1;
    found.px[k] = rec.px; found.py[k] = rec.py; found.pz[k] = rec.pz;
    found.nx[k] = rec.nx; found.ny[k] = rec.ny; found.nz[k] = rec.nz;
    found.depth[k] = rec.depth;
    found.flags[k] = rec.flags;
  }
  // A sphere whose link value overflowed is non-finite to the AFU, which pairs it with
  // nothing: it is listed as bad, like a sphere the policy rejects.
  if (!last_.rangeSpheres.empty()) {
    std::vector<std::pair<std::uint32_t, std::uint8_t>> bad;
    for (std::size_t k = 0; k < out.badSpheres.size(); ++k) bad.emplace_back(out.badSpheres[k], out.badFlags[k]);
    for (auto k : last_.rangeSpheres) bad.emplace_back(members_[k], contract::REC_HOST_RANGE);
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
