#include "driver/manifest.hpp"

#include <fstream>
#include <stdexcept>

namespace collide::driver {

Manifest loadManifest(const std::filesystem::path& afuDir) {
  const auto file = afuDir / "manifest.json";
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": no manifest (is " + afuDir.string() + " a generated AFU folder?)");
  Manifest m;
  try {
    m.raw = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(file.string() + ": not valid JSON: " + e.what());
  }
  const auto fmt = m.raw.value(nlohmann::json::json_pointer("/link/format"), std::string("binary32"));
  if (fmt == "binary32") m.format = LinkFormat::Binary32;
  else if (fmt == "binary64") m.format = LinkFormat::Binary64;
  else throw std::runtime_error(file.string() + ": link.format: expected binary32 or binary64, got " + fmt);
  const auto ms = m.raw.value(nlohmann::json::json_pointer("/afu/maxSpheres"), 65536LL);
  if (ms < 1 || ms > 65536) throw std::runtime_error(file.string() + ": afu.maxSpheres: expected 1..65536");
  m.maxSpheres = static_cast<std::uint32_t>(ms);
  return m;
}

}  // namespace collide::driver
