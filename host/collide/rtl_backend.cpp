#include "collide/rtl_backend.hpp"

#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>


namespace collide {

RtlBackend::RtlBackend(const std::filesystem::path& afuDir, const link::LinkParams& link,
                       driver::DriverOptions options, const driver::AfuPortOptions& portOptions)
    : port_(std::make_unique<driver::WallClockWatchdog>(driver::makeAfuPort(afuDir, portOptions),  // throws AfuUnavailable first
                                                        portOptions.wallLimitS)) {
  driver_ = std::make_unique<driver::AfuDriver>(*port_, link, driver::withManifest(options, driver::afuManifest(afuDir)));
}

RtlBackend::RtlBackend(std::unique_ptr<driver::AfuPort> port, const link::LinkParams& link,
                       const driver::DriverOptions& options, double wallLimitS)
    : port_(std::make_unique<driver::WallClockWatchdog>(std::move(port), wallLimitS)),
      driver_(std::make_unique<driver::AfuDriver>(*port_, link, options)) {}

void requireAtLeastLinkBound(const driver::RunStats& r, const std::string& linkName) {
  // Both are sums of a few doubles: allow their rounding, nothing more.
  if (r.modelledNs >= r.linkBoundNs * (1 - 1e-12)) return;
  std::ostringstream m;
  m << std::setprecision(17) << "internal error: modelled run time " << r.modelledNs << " ns is below its link bound "
    << r.linkBoundNs << " ns (link " << linkName << ", " << r.readLines << " lines read, " << r.writeLines
    << " written, status after " << r.statusCycle << " cycles); the link model, driver::linkBoundNs or the "
    << "driver's protocol is wrong";
  throw std::logic_error(m.str());
}

void RtlBackend::runOne(const SphereTable& spheres, const PairList& pairs, ContactSet& out) {
  port_->arm();
  last_ = driver_->run(spheres, pairs);
  requireAtLeastLinkBound(last_.stats, driver_->link().params().name);
  out = driver_->toContactSet(last_, pairs.size());
  batch_.add(last_.status, last_.stats);
}

void RtlBatchStats::add(const driver::StatusLine& s, const driver::RunStats& r, std::size_t n) {
  runs += n;
  driver::accumulate(counters, s);
  driver::accumulate(stats, r);
}

void RtlBackend::collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) {
  batch_ = RtlBatchStats{};
  const std::size_t n = pairs.size();
  const std::size_t maxSpheres = driver_->options().maxSpheres;
  constexpr std::size_t maxPairs = (std::size_t{1} << 24) - 1;
  if (n == 0) {  // nothing to collide: no AFU call
    out.resize(0);
    out.format = format();
    return;
  }
  if (spheres.size() <= maxSpheres && n <= maxPairs) {
    runOne(spheres, pairs, out);
    return;
  }

  // Split: greedily add pairs while their spheres fit in one AFU table.
  out.resize(n);
  out.format = format();
  local_.assign(spheres.size(), -1);
  std::vector<std::uint32_t> used;  // globals mapped in this chunk (to clear local_)
  auto flush = [&] {
    if (chunkPairs_.size() == 0) return;
    runOne(chunkSpheres_, chunkPairs_, chunkOut_);
    for (std::size_t k = 0; k < chunkOrigin_.size(); ++k) {
      out.setEntry(chunkOrigin_[k], chunkOut_, k);
    }
    for (auto g : used) local_[g] = -1;
    used.clear();
    chunkSpheres_.clear();
    chunkPairs_.clear();
    chunkOrigin_.clear();
  };
  auto map = [&](std::uint32_t g) {
    if (local_[g] < 0) {
      local_[g] = static_cast<std::int32_t>(chunkSpheres_.size());
      chunkSpheres_.push(spheres.x[g], spheres.y[g], spheres.z[g], spheres.r[g]);
      used.push_back(g);
    }
    return static_cast<std::uint32_t>(local_[g]);
  };
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t i = pairs.i[k], j = pairs.j[k];
    if (i >= spheres.size() || j >= spheres.size())
      throw std::invalid_argument("rtl: pair " + std::to_string(k) + " names a sphere beyond the table of " +
                                  std::to_string(spheres.size()));
    const std::size_t fresh = (local_[i] < 0) + (local_[j] < 0 && j != i);
    if (chunkSpheres_.size() + fresh > maxSpheres || chunkPairs_.size() == maxPairs) flush();
    const std::uint32_t li = map(i), lj = map(j);
    chunkPairs_.push(li, lj);
    chunkOrigin_.push_back(k);
  }
  flush();
}

}  // namespace collide
