#pragma once
// The named link presets: what `collide --link NAME`, a scene's "link": {"type": NAME}
// and `collide info --links` know. The numbers, each with its source, are in
// link_presets.cpp (the LinkParams factories).
#include <string>
#include <vector>

#include "link/link_params.hpp"

namespace collide::link {

struct LinkPreset {
  std::string name;                  // canonical; LinkParams::name
  std::vector<std::string> aliases;  // other names accepted for it
  std::string description;           // one line
  std::vector<std::string> sources;  // where each number comes from; assumptions say so
  LinkParams params;
};

// The link of an rtl run that names none (no scene "link", no --link), for every command:
// preloaded data, so modelled time is the AFU's own unless a link is asked for.
inline constexpr const char* kDefaultPreset = "ideal";

// Every preset, in a fixed order (ideal first, then by generation).
const std::vector<LinkPreset>& presets();
// Names and aliases, in registry order: the accepted spellings.
std::vector<std::string> presetNames();
// The preset called (or aliased) `name`, or nullptr.
const LinkPreset* findPreset(const std::string& name);
// Its parameters; throws std::invalid_argument listing the known names.
LinkParams presetParams(const std::string& name);

}  // namespace collide::link
