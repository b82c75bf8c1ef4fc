// The AFU factory of a build without a Verilated AFU: says so, with the way to get one.
#include "driver/afu_factory.hpp"

namespace collide::driver {

std::string builtInAfuPreset() { return ""; }
std::string builtInAfuManifest() { return ""; }
std::string builtInAfuTiming(std::string& why) {
  why = "this collide has no AFU built in";
  return "";
}

std::unique_ptr<AfuPort> makeAfuPort(const std::filesystem::path& afuDir, const AfuPortOptions&) {
  throw AfuUnavailable(
      "no AFU available: this collide was built without a Verilated AFU, so the rtl backend "
      "cannot run" + (afuDir.empty() ? std::string() : " (asked for " + afuDir.string() + ")") +
      ". Generate an AFU into generated/<preset>/ and configure host/ with "
      "-DCOLLIDE_AFU_PRESET=<preset>.");
}

}  // namespace collide::driver
