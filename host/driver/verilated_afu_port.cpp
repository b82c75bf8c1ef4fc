// The AFU factory of a build with a Verilated AFU (cmake/CollideVerilate.cmake compiles
// this file with the model's class and header, the preset name, the folder it was built
// from and that folder's manifest.json text).
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include COLLIDE_AFU_VTOP_HEADER
#include "driver/verilated_afu_port.hpp"
#include "util/input_file.hpp"
#include "util/json_input.hpp"

#ifndef COLLIDE_AFU_PRESET
#error "COLLIDE_AFU_PRESET must name the Verilated preset"
#endif

namespace collide::driver {

// Generated next to the build (CollideVerilate.cmake).
const char* collideBuiltInManifest();
const char* collideBuiltInTiming();
const char* collideBuiltInTimingNote();

std::string builtInAfuPreset() { return COLLIDE_AFU_PRESET; }
std::string builtInAfuManifest() { return collideBuiltInManifest(); }
std::string builtInAfuTiming(std::string& why) {
  why = collideBuiltInTimingNote();
  return collideBuiltInTiming();
}

namespace {

// `afuDir` must hold the configuration this binary was built from: its manifest must equal
// the one compiled in (the folder may be a copy, e.g. a scratch checkout of generated/).
void requireSameAfu(const std::filesystem::path& afuDir) {
  const std::string built = std::string(COLLIDE_AFU_DIR) + " (preset " + COLLIDE_AFU_PRESET + ")";
  if (afuDir.empty()) return;  // the built-in one
  const auto file = afuDir / "manifest.json";
  if (!std::filesystem::exists(file))
    throw AfuUnavailable("no AFU available for " + afuDir.string() + ": no manifest.json there; this collide was built with " + built);
  nlohmann::json asked, have;
  try {
    std::ifstream in = util::openInput(file);
    asked = util::parseJson(in, file.string(), "manifest");  // bounded depth: compared below
    have = util::parseJson(collideBuiltInManifest(), "the built-in AFU's manifest", "manifest");
  } catch (const std::runtime_error& e) {
    throw AfuUnavailable(e.what());
  }
  if (asked != have)
    throw AfuUnavailable("no AFU available for " + afuDir.string() + ": its manifest.json differs from the AFU this collide was built with, " +
                         built + "; reconfigure host/ with -DCOLLIDE_AFU_DIR=" + afuDir.string() +
                         " (or the matching -DCOLLIDE_AFU_PRESET) and rebuild");
}

}  // namespace

std::unique_ptr<AfuPort> makeAfuPort(const std::filesystem::path& afuDir, const AfuPortOptions& options) {
  requireSameAfu(afuDir);
  return std::make_unique<VerilatedAfuPort<COLLIDE_AFU_VTOP>>(options);
}

}  // namespace collide::driver
