#pragma once
// The AFU's clock for modelled times: the target (the link's clock_mhz, the clock the design is
// built for) unless its Verilog is measured to reach less, or a study names one (--clock-mhz).
//
// What the Verilog reaches comes from its timing.json (bench/area/reached_clock.py): per FPGA
// family, the slowest block's cells-only delay by the timing proxy and the clock that allows (an
// upper bound: no routing), and a routing-calibrated estimate (a model). The build compiles it in
// only for the Verilog it names by SHA-256 (CollideVerilate.cmake). The time uses the proxy's
// clock: the bound, so an AFU is never timed slower than its cells allow.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace collide::driver {

inline constexpr const char* kClockFamily = "cyclonev";  // the generator's default family (FpgaFamily)

struct ReachedClock {
  std::string family;      // the proxy's cell delays: cyclonev or arriav
  std::string block;       // the slowest block (its module)
  double cellsNs = 0;      // its cells-only path
  double proxyMHz = 0;     // 1e3 / cellsNs
  double routedMHz = 0;    // proxyMHz / the routing model's ratio
  std::string commit;      // of the Verilog the proxy timed
};

// From timing.json text, for `family`; throws std::runtime_error naming `what` on bad JSON or
// a family it does not hold.
ReachedClock parseReachedClock(const std::string& text, const std::string& family, const std::string& what);

struct ClockChoice {
  double targetMHz = 0;                // what the design is built for (the link's clock)
  double usedMHz = 0;                  // what the modelled times use
  std::optional<ReachedClock> reached; // none: not measured (why in `unknownWhy`)
  std::string unknownWhy;
  bool study = false;                  // --clock-mhz named it
  bool reachesTarget() const { return reached && reached->proxyMHz >= targetMHz; }
  std::string describe() const;        // one line for the run's report
  nlohmann::json toJson() const;       // the summary's afu.clock
};

ClockChoice chooseClock(double targetMHz, const std::optional<ReachedClock>& reached, const std::string& unknownWhy,
                        const std::optional<double>& studyMHz);

// "Cyclone V" for cyclonev, "Arria V" for arriav.
std::string familyName(const std::string& family);

// The built-in AFU's reached clock (its compiled-in timing.json), or none with the reason.
std::optional<ReachedClock> builtInReachedClock(std::string& unknownWhy);

}  // namespace collide::driver
