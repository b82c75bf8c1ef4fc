#pragma once
// The AFU's clock, shared by `run`, `pairs` and `spheres`: the link's clock_mhz is the target the
// design is built for; the modelled times use the lower of it and what the built-in AFU's Verilog
// reaches by the timing proxy (driver/afu_clock.hpp), unless --clock-mhz names one for a study.
// The link's own rates and latencies stay in ns. Checked as a link's clock_mhz is.
#include <optional>
#include <stdexcept>
#include <string>

#include "driver/afu_clock.hpp"
#include "link/link_params.hpp"

namespace collide::cli {

inline driver::ClockChoice applyClockOption(link::LinkParams& lp, const std::optional<double>& mhz) {
  std::string why;
  const auto reached = driver::builtInReachedClock(why);
  const auto choice = driver::chooseClock(lp.clockMHz, reached, why, mhz);
  lp.clockMHz = choice.usedMHz;
  try {
    lp.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(mhz ? "--clock-mhz: " : "the AFU's reached clock: ") + e.what());
  }
  return choice;
}

// The refusal where no AFU runs: the clock would time nothing.
inline void refuseClockOption(const std::optional<double>& mhz, const std::string& where) {
  if (mhz) throw std::invalid_argument("--clock-mhz applies to the AFU (--afu DIR or --backend rtl), not to " + where);
}

}  // namespace collide::cli
