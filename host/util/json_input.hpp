#pragma once
// Reading a JSON file (a scene, a manifest) with bounded nesting. nlohmann's parser is
// iterative, but everything after it (dump, comparison, our readers) recurses once per
// level, so a file nested 100,000 deep would overflow the stack. Deeper than
// kMaxJsonDepth levels is an error naming the file and the key path where it happened,
// raised while parsing (the parser callback), before any such value exists.
#include <istream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace collide::util {

// Scenes and manifests need 5 or 6 levels; 64 leaves room and no stack at risk.
constexpr int kMaxJsonDepth = 64;

struct JsonInputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `what` names the input in errors ("scenes/x.json"), `root` starts key paths ("scene").
// Throws JsonInputError "<what>: not valid JSON: ..." or
// "<what>: <root>.a.b[3]...: nested deeper than 64 levels".
nlohmann::json parseJson(std::istream& in, const std::string& what, const std::string& root);
nlohmann::json parseJson(const std::string& text, const std::string& what, const std::string& root);

}  // namespace collide::util
