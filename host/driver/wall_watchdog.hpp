#pragma once
// The wall-clock watchdog of an AFU run. The driver's own watchdog counts simulated cycles
// (DriverOptions::watchdogCycles), which only bounds wall time while idle waits are
// skipped: with skipping off, or an AFU that never goes idle, 50 million stepped cycles of
// the Verilated AFU take about 20 minutes. WallClockWatchdog wraps the AfuPort, is armed at
// the start of each call (a pair run, or a world collision with all its slabs), and throws AfuError naming itself once a run has taken longer
// than its limit of wall-clock time. The rtl backend wraps every port in one.
#include <chrono>
#include <cstdint>
#include <memory>

#include "driver/afu_port.hpp"

namespace collide::driver {

// Generous: the 100-step diamond over QPI takes about 1 s. --wall-limit SECONDS or a
// scene's "wall_limit_s" sets it, within (0, kMaxWallLimitS].
inline constexpr double kDefaultWallLimitS = 600.0;
inline constexpr double kMaxWallLimitS = 1e6;

class WallClockWatchdog final : public AfuPort {
 public:
  // Throws std::invalid_argument if the limit is not in (0, kMaxWallLimitS].
  WallClockWatchdog(std::unique_ptr<AfuPort> port, double limitSeconds);

  // Starts the clock of one run (the rtl backend calls it before every driver run).
  void arm();

  void reset() override { port_->reset(); }
  void setInputs(const link::LinkToAfu& in) override { port_->setInputs(in); }
  link::AfuToLink evalOutputs() override { return port_->evalOutputs(); }
  void clockEdge() override;
  bool idle() const override { return port_->idle(); }
  bool reportsIdle() const override { return port_->reportsIdle(); }
  void skipIdleCycles(std::uint64_t n) override;

  AfuPort& inner() { return *port_; }
  double limitSeconds() const { return limitS_; }

 private:
  void check();

  std::unique_ptr<AfuPort> port_;
  double limitS_;
  std::chrono::steady_clock::time_point start_;
  std::uint64_t edges_ = 0, skipped_ = 0;
};

}  // namespace collide::driver
