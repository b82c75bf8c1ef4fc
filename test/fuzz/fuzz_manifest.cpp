// libFuzzer target: a generated AFU folder's manifest.json, as the host reads it before
// driving the AFU (driver/manifest.hpp).
#include <stdexcept>
#include <string>

#include "driver/manifest.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)collide::driver::parseManifest(text, collide::fuzz::kInputName);
  } catch (const std::runtime_error& e) {  // JsonInputError and the reader's own errors
    collide::fuzz::requireNamed("manifest error", e.what());
  }
  return 0;
}
