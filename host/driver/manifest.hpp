#pragma once
// The generator's manifest (generated/<preset>/manifest.json). The host reads only what
// crosses the link contract: link.format and afu.maxSpheres; the rest is printed by
// `collide info`.
#include <cstdint>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "collide/batch.hpp"

namespace collide::driver {

struct Manifest {
  nlohmann::json raw;
  LinkFormat format = LinkFormat::Binary32;
  std::uint32_t maxSpheres = 65536;
};

// Throws std::runtime_error naming the file: missing, unreadable, bad JSON, bad field.
Manifest loadManifest(const std::filesystem::path& afuDir);

}  // namespace collide::driver
