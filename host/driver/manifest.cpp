#include "driver/manifest.hpp"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "afu_contract.hpp"
#include "batch/pair_kinds.hpp"
#include "driver/afu_layout.hpp"
#include "util/echo.hpp"
#include "util/input_file.hpp"
#include "util/json_input.hpp"

namespace collide::driver {

namespace {
Manifest fromJson(nlohmann::json raw, const std::string& file);
}

Manifest loadManifest(const std::filesystem::path& afuDir) {
  const auto file = afuDir / "manifest.json";
  if (!std::filesystem::exists(file))
    throw std::runtime_error(file.string() + ": no manifest (is " + afuDir.string() + " a generated AFU folder?)");
  std::ifstream in = util::openInput(file);  // names a directory as one
  return fromJson(util::parseJson(in, file.string(), "manifest"), file.string());  // bounded depth
}

Manifest parseManifest(const std::string& text, const std::string& what) {
  return fromJson(util::parseJson(text, what, "manifest"), what);
}

namespace {
Manifest fromJson(nlohmann::json raw, const std::string& file) {
  Manifest m;
  m.raw = std::move(raw);
  using nlohmann::json;
  auto bad = [&](const std::string& what) { throw std::runtime_error(file + ": " + what); };
  if (!m.raw.is_object()) bad("expected a JSON object, got " + util::echoJson(m.raw));
  // A field of the wrong type is an error naming the file and the field, not nlohmann's.
  auto at = [&](const char* ptr, auto dflt) {
    try {
      return m.raw.value(json::json_pointer(ptr), dflt);
    } catch (const json::exception&) {
      std::string key(ptr + 1);  // "/link/format" -> "link.format"
      std::replace(key.begin(), key.end(), '/', '.');
      throw std::runtime_error(file + ": " + key + ": expected a " + json(dflt).type_name() + ", got " +
                               util::echoJson(m.raw.at(json::json_pointer(ptr))));
    }
  };
  const auto fmt = at("/link/format", std::string("binary32"));
  if (!linkFormatFromString(fmt, m.format))
    bad("link.format: expected binary16, bfloat16, binary32 or binary64, got " + util::clip(fmt));
  const auto layout = at("/buffers/records/layout", std::string("full"));
  if (layout == "full") m.records = contract::LAYOUT_FULL;
  else if (layout == "derived") m.records = contract::LAYOUT_DERIVED;
  else if (layout == "full-masked") m.records = contract::LAYOUT_FULL_MASKED;
  else if (layout == "derived-masked") m.records = contract::LAYOUT_DERIVED_MASKED;
  else bad("buffers.records.layout: expected full, derived, full-masked or derived-masked, got " + util::clip(layout));
  // The record size the manifest states must be the one the contract's rule gives.
  const BufferLayout lay{m.format, m.records};
  const auto rb = at("/buffers/recordBytes", static_cast<long long>(lay.recordBytes()));
  if (rb != static_cast<long long>(lay.recordBytes()))
    bad("buffers.recordBytes " + std::to_string(rb) + " disagrees with " + std::to_string(lay.recordBytes()) +
        " for " + util::clip(layout) + " records on a " + fmt + " link");
  m.arith.link = numberFormat(m.format);
  m.arith.compute = format::NumberFormat{static_cast<int>(at("/scpu/format/expBits", 8LL)),
                                         static_cast<int>(at("/scpu/format/sigBits", 24LL))};
  const auto dist = at("/scpu/distance", std::string("sqrt-recip"));
  if (dist == "sqrt-recip") m.arith.distance = DistanceMethod::SqrtThenRecip;
  else if (dist == "rsqrt") m.arith.distance = DistanceMethod::Rsqrt;
  else if (dist == "robust") m.arith.distance = DistanceMethod::Robust;
  else bad("scpu.distance: expected sqrt-recip, rsqrt or robust, got " + util::clip(dist));
  if (lay.derived()) {
    if (at("/scpu/rounding", std::string("RNE")) != "RNE" || !at("/scpu/subnormals", true))
      bad("derived records need an SCPU that rounds to nearest even with subnormals kept");
    const auto& c = m.arith.compute;
    if (c.expBits < 3 || c.expBits > 11 || c.sigBits < 3 || !c.emulatedExactlyByBinary64() ||
        c.expBits > m.arith.link.expBits || c.sigBits > m.arith.link.sigBits)
      bad("derived records: the host cannot reproduce scpu.format " + format::describe(c) + " exactly");
  }
  const auto ms = at("/afu/maxSpheres", 65536LL);
  if (ms < 1 || ms > 65536) bad("afu.maxSpheres: expected 1..65536, got " + std::to_string(ms));
  m.maxSpheres = static_cast<std::uint32_t>(ms);
  m.world = at("/afu/world", false);
  if (m.world && (m.records == contract::LAYOUT_FULL_MASKED || m.records == contract::LAYOUT_DERIVED_MASKED))
    bad("afu.world: world mode needs an indexed record layout, the manifest says " + layout);
  m.runQueue = at("/afu/runQueue", false);
  m.pairKinds = at("/afu/pairKinds", std::vector<std::string>{"sphere-sphere"});
  for (const auto& k : m.pairKinds)
    if (!isPairKind(k)) bad("afu.pairKinds: expected " + pairKindList() + ", got " + util::clip(k));
  if (m.runQueue && !m.world) bad("afu.runQueue: a run queue needs world mode (afu.world)");
  if (m.world && ms > (1LL << contract::TAG_WORLD_INDEX_BITS))
    bad("afu.world: world mode holds at most " + std::to_string(1u << contract::TAG_WORLD_INDEX_BITS) + " spheres, afu.maxSpheres is " + std::to_string(ms));
  return m;
}
}  // namespace

}  // namespace collide::driver
