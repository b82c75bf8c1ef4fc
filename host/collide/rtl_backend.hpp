#pragma once
// `rtl` backend: the generated AFU (Verilated) behind the link model, through the driver.
// Construction fails with driver::AfuUnavailable when this build has no AFU.
#include <filesystem>
#include <memory>

#include "collide/backend.hpp"
#include "driver/afu_driver.hpp"
#include "driver/afu_factory.hpp"
#include "link/link_params.hpp"

namespace collide {

class RtlBackend final : public CollisionBackend {
 public:
  RtlBackend(const std::filesystem::path& afuDir, const link::LinkParams& link,
             driver::DriverOptions options = {}, const driver::AfuPortOptions& portOptions = {});
  // For tests and other models: any AfuPort, owned by the backend.
  RtlBackend(std::unique_ptr<driver::AfuPort> port, const link::LinkParams& link,
             const driver::DriverOptions& options);

  std::string name() const override { return "rtl"; }
  LinkFormat format() const override { return driver_->options().format; }
  void collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) override;

  // Statistics of the last batch (modelled time, cycles, status counters).
  const driver::RunResult& lastRun() const { return last_; }

 private:
  std::unique_ptr<driver::AfuPort> port_;
  std::unique_ptr<driver::AfuDriver> driver_;
  driver::RunResult last_;
};

}  // namespace collide
