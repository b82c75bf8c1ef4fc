// libFuzzer target: a scene file (JSON), as `collide run --scene FILE` reads it.
#include <string>

#include "fuzz_input.hpp"
#include "scene/json_reader.hpp"
#include "scene/scene.hpp"
#include "util/json_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // loadScene's two steps, without the file: bounded-depth JSON, then the scene's rules.
    const auto j = collide::util::parseJson(text, collide::fuzz::kInputName, "scene");
    (void)collide::scene::parseScene(j);
  } catch (const collide::util::JsonInputError& e) {
    collide::fuzz::requireNamed("JsonInputError", e.what());
  } catch (const collide::scene::SceneError& e) {
    collide::fuzz::requireNamed("SceneError", e.what(), "scene");  // its key path
  }
  return 0;
}
