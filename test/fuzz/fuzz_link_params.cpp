// libFuzzer target: link parameters, the object a scene's "link" key holds (over a named
// preset, as the scene loader reads it).
#include <stdexcept>
#include <string>

#include "fuzz_input.hpp"
#include "link/link_params.hpp"
#include "util/json_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto j = collide::util::parseJson(text, collide::fuzz::kInputName, collide::fuzz::kInputName);
    auto p = collide::link::linkParamsFromJson(j, collide::fuzz::kInputName, collide::link::LinkParams::qpi());
    p.validate();
    // What the link model derives from accepted parameters must be usable numbers.
    (void)p.nsToCycles(p.cycleNs());
    (void)p.aggregateReadGBps();
    (void)p.aggregateWriteGBps();
  } catch (const collide::util::JsonInputError& e) {
    collide::fuzz::requireNamed("JsonInputError", e.what());
  } catch (const std::invalid_argument& e) {
    collide::fuzz::requireNamed("link parameter error", e.what());
  }
  return 0;
}
