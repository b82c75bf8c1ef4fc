#pragma once
// Where the rtl backend gets its AFU. Implemented by no_afu.cpp (no Verilated model in
// this build) or by verilated_afu_port.cpp (cmake -DCOLLIDE_AFU_PRESET=<preset>).
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "driver/afu_port.hpp"

namespace collide::driver {

struct AfuUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct AfuPortOptions {
  std::filesystem::path traceFile;  // VCD/FST; empty = no trace (needs COLLIDE_AFU_TRACE)
};

// The preset compiled into this binary, or "" if none.
std::string builtInAfuPreset();

// An AFU for the generated configuration in `afuDir`. Throws AfuUnavailable if this build
// has no Verilated AFU or if `afuDir` is not the configuration it was built from.
std::unique_ptr<AfuPort> makeAfuPort(const std::filesystem::path& afuDir, const AfuPortOptions& options);

}  // namespace collide::driver
