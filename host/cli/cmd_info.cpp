#include <iostream>

#include "cli/commands.hpp"
#include "driver/afu_factory.hpp"
#include "driver/manifest.hpp"

namespace collide::cli {

int runInfo(const InfoOptions& o) {
  try {
    const auto m = driver::loadManifest(o.afu);
    std::cout << m.raw.dump(2) << "\n";
    const auto preset = driver::builtInAfuPreset();
    std::cerr << "host: link format " << toString(m.format) << ", max spheres " << m.maxSpheres
              << "; Verilated AFU in this build: " << (preset.empty() ? "none" : preset) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "collide info: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace collide::cli
