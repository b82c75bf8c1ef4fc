#pragma once
// The generator's manifest (generated/<preset>/manifest.json). The host reads what crosses
// the link contract: link.format, the record layout (buffers.records), afu.maxSpheres, and
// for derived records the SCPU's arithmetic it must reproduce (scpu.format, rounding,
// subnormals, distance); the rest is printed by `collide info`.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/contact_rebuild.hpp"
#include "format/link_format.hpp"

namespace collide::driver {

struct Manifest {
  nlohmann::json raw;
  LinkFormat format = LinkFormat::Binary32;
  std::uint32_t records = 0;   // contract::LAYOUT_*
  ComputeArith arith;          // what rebuilds derived records
  std::uint32_t maxSpheres = 65536;
  bool world = false;          // afu.world: world mode (MODE_WORLD) is built
  bool runQueue = false;       // afu.runQueue: a start during a run queues one more (world mode)
  // afu.pairKinds: the pair kinds it has units for (batch/pair_kinds.hpp; absent: sphere-sphere)
  std::vector<std::string> pairKinds{"sphere-sphere"};
};

// Throws std::runtime_error naming the file: missing, unreadable, bad JSON, bad field.
Manifest loadManifest(const std::filesystem::path& afuDir);
// The same from JSON text; `what` names it in errors.
Manifest parseManifest(const std::string& text, const std::string& what);

}  // namespace collide::driver
