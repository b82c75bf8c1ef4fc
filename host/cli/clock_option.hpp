#pragma once
// --clock-mhz, shared by `run`, `pairs` and `spheres`: the AFU's same cycles timed at another
// clock than the link preset's (for example the one the timing proxy says its cells allow);
// the link's own rates and latencies stay in ns. Checked as a link's clock_mhz is.
#include <optional>
#include <stdexcept>
#include <string>

#include "link/link_params.hpp"

namespace collide::cli {

inline void applyClockOption(link::LinkParams& lp, const std::optional<double>& mhz) {
  if (!mhz) return;
  lp.clockMHz = *mhz;
  try {
    lp.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--clock-mhz: ") + e.what());
  }
}

// The refusal where no AFU runs: the clock would time nothing.
inline void refuseClockOption(const std::optional<double>& mhz, const std::string& where) {
  if (mhz) throw std::invalid_argument("--clock-mhz applies to the AFU (--afu DIR or --backend rtl), not to " + where);
}

}  // namespace collide::cli
