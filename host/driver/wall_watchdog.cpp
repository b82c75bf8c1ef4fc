#include "driver/wall_watchdog.hpp"

#include <sstream>
#include <stdexcept>

#include "driver/afu_driver.hpp"

namespace collide::driver {

WallClockWatchdog::WallClockWatchdog(std::unique_ptr<AfuPort> port, double limitSeconds)
    : port_(std::move(port)), limitS_(limitSeconds), start_(std::chrono::steady_clock::now()) {
  if (!(limitSeconds > 0 && limitSeconds <= kMaxWallLimitS)) {
    std::ostringstream m;
    m << "wall-clock limit: " << limitSeconds << " s is outside (0, " << kMaxWallLimitS << "] s";
    throw std::invalid_argument(m.str());
  }
}

void WallClockWatchdog::arm() {
  start_ = std::chrono::steady_clock::now();
  edges_ = skipped_ = 0;
}

void WallClockWatchdog::clockEdge() {
  port_->clockEdge();
  // Reading the clock costs tens of nanoseconds, an edge of the Verilated AFU tens of
  // microseconds: every 64th edge keeps the check invisible even for the C++ model AFU.
  if ((++edges_ & 63) == 0) check();
}

void WallClockWatchdog::skipIdleCycles(std::uint64_t n) {
  port_->skipIdleCycles(n);
  skipped_ += n;
  check();
}

void WallClockWatchdog::check() {
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start_;
  if (took.count() <= limitS_) return;
  std::ostringstream m;
  m << "AFU hung: no status line after " << took.count() << " s of wall-clock time (wall-clock watchdog, limit "
    << limitS_ << " s: --wall-limit SECONDS or the scene's \"wall_limit_s\"); " << edges_ << " cycles evaluated, "
    << skipped_ << " skipped, AFU " << (port_->idle() ? "idle-waiting" : "busy");
  throw AfuError(m.str(), StatusLine{});
}

}  // namespace collide::driver
