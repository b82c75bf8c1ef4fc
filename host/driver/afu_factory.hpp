#pragma once
// Where the rtl backend gets its AFU. Implemented by no_afu.cpp (no Verilated model in
// this build) or by verilated_afu_port.cpp (cmake -DCOLLIDE_AFU_PRESET=<preset>).
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "driver/afu_port.hpp"
#include "driver/manifest.hpp"
#include "driver/wall_watchdog.hpp"
#include "link/link_params.hpp"

namespace collide::driver {

struct AfuUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct AfuPortOptions {
  // Waveform of the whole run: .fst or .vcd, as the model was Verilated
  // (-DCOLLIDE_AFU_TRACE=FST|VCD); empty = no trace.
  std::filesystem::path traceFile;
  // Simulated clock for the trace's time axis: the link model's clock (callers pass
  // LinkParams::clockMHz; the default is the link's own).
  double clockMHz = link::kDefaultClockMHz;
  // Wall-clock limit of one AFU run, in seconds. Not the port's own business: the rtl
  // backend wraps the port in a WallClockWatchdog with it.
  double wallLimitS = kDefaultWallLimitS;
};

// The preset compiled into this binary, or "" if none.
std::string builtInAfuPreset();
// The manifest.json text of the AFU compiled into this binary, or "" if none (what an
// empty AFU folder means: the built-in one).
std::string builtInAfuManifest();
// The timing.json text of the AFU compiled into this binary (the clock its Verilog reaches), or
// "" with the reason in `why` (no AFU, no timing.json, or one describing other Verilog).
std::string builtInAfuTiming(std::string& why);
// The manifest of the AFU in `afuDir`, or (empty) of the one built in; errors as
// loadManifest / parseManifest.
inline Manifest afuManifest(const std::filesystem::path& afuDir) {
  return afuDir.empty() ? parseManifest(builtInAfuManifest(), "the built-in AFU's manifest") : loadManifest(afuDir);
}

// An AFU for the generated configuration in `afuDir` (empty: the built-in one). Throws
// AfuUnavailable if this build has no Verilated AFU or if `afuDir`'s manifest differs from
// the configuration it was built from.
std::unique_ptr<AfuPort> makeAfuPort(const std::filesystem::path& afuDir, const AfuPortOptions& options);

}  // namespace collide::driver
