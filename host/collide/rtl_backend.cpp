#include "collide/rtl_backend.hpp"

#include "driver/manifest.hpp"

namespace collide {

namespace {
driver::DriverOptions fromManifest(const std::filesystem::path& dir, driver::DriverOptions o) {
  const auto m = driver::loadManifest(dir);
  o.format = m.format;
  o.maxSpheres = m.maxSpheres;
  return o;
}
}  // namespace

RtlBackend::RtlBackend(const std::filesystem::path& afuDir, const link::LinkParams& link,
                       driver::DriverOptions options, const driver::AfuPortOptions& portOptions)
    : port_(driver::makeAfuPort(afuDir, portOptions)) {  // throws AfuUnavailable first
  driver_ = std::make_unique<driver::AfuDriver>(*port_, link, fromManifest(afuDir, options));
}

RtlBackend::RtlBackend(std::unique_ptr<driver::AfuPort> port, const link::LinkParams& link,
                       const driver::DriverOptions& options)
    : port_(std::move(port)), driver_(std::make_unique<driver::AfuDriver>(*port_, link, options)) {}

void RtlBackend::collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) {
  last_ = driver_->run(spheres, pairs);
  out = driver_->toContactSet(last_, pairs.size());
}

}  // namespace collide
