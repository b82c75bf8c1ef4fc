#include "util/echo.hpp"

#include <nlohmann/json.hpp>

namespace collide::util {

namespace {
// Back up from `n` to the start of a UTF-8 sequence, so the clipped text stays valid UTF-8.
std::size_t boundary(std::string_view s, std::size_t n) {
  while (n > 0 && n < s.size() && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;
  return n;
}

// Appends j to out until out holds more than `max` characters. Each nesting level adds at
// least one character, so the recursion is at most max + 1 deep.
void put(const nlohmann::json& j, std::string& out, std::size_t max) {
  if (out.size() > max) return;
  if (j.is_object() || j.is_array()) {
    const bool obj = j.is_object();
    out += obj ? '{' : '[';
    bool first = true;
    for (auto it = j.begin(); it != j.end() && out.size() <= max; ++it) {
      if (!first) out += ',';
      first = false;
      if (obj) {
        put(nlohmann::json(it.key()), out, max);
        out += ':';
      }
      put(*it, out, max);
    }
    out += obj ? '}' : ']';
  } else if (j.is_string()) {
    const auto& s = j.get_ref<const std::string&>();
    const std::size_t room = max + 1 - out.size();  // a prefix is all that can be shown
    out += nlohmann::json(s.substr(0, boundary(s, std::min(s.size(), room)))).dump();
  } else {
    out += j.dump();
  }
}
}  // namespace

std::string clip(std::string_view s, std::size_t max) {
  if (s.size() <= max) return std::string(s);
  return std::string(s.substr(0, boundary(s, max))) + "... (" + std::to_string(s.size()) + " bytes)";
}

std::string echoJson(const nlohmann::json& j, std::size_t max) {
  std::string out;
  put(j, out, max);
  if (out.size() <= max) return out;
  return out.substr(0, boundary(out, max)) + "...";
}

}  // namespace collide::util
