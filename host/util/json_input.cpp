#include "util/json_input.hpp"

#include <vector>

#include "util/echo.hpp"

namespace collide::util {

namespace {

// The key path of the value being parsed, kept from the parser's events.
class DepthGuard {
 public:
  DepthGuard(const std::string& what, const std::string& root) : what_(what), root_(root) {}

  bool operator()(int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        element();
        if (depth + 1 > kMaxJsonDepth)
          throw JsonInputError(what_ + ": " + path() + ": nested deeper than " + std::to_string(kMaxJsonDepth) +
                               " levels");
        frames_.push_back({event == E::array_start, "", 0});
        break;
      case E::key:
        if (!frames_.empty()) frames_.back().key = clip(parsed.get_ref<const std::string&>(), 40);
        break;
      case E::value:
        element();
        break;
      case E::object_end:
      case E::array_end:
        if (!frames_.empty()) frames_.pop_back();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool array;
    std::string key;    // objects: the key being read
    std::size_t count;  // arrays: elements begun so far
  };
  void element() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().count;
  }
  std::string path() const {
    std::string p = root_;
    for (const auto& f : frames_) p += f.array ? "[" + std::to_string(f.count - 1) + "]" : "." + f.key;
    return p;
  }

  const std::string& what_;
  const std::string& root_;
  std::vector<Frame> frames_;
};

template <typename Input>
nlohmann::json parse(Input&& in, const std::string& what, const std::string& root) {
  DepthGuard guard(what, root);
  try {
    return nlohmann::json::parse(std::forward<Input>(in), std::ref(guard));
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann quotes the last token it read, which may be a whole line: clipped.
    throw JsonInputError(what + ": not valid JSON: " + clip(e.what(), 4 * kEchoChars));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond binary64 (1e400): nlohmann refuses it with out_of_range, not parse_error.
    throw JsonInputError(what + ": a number out of binary64's range: " + clip(e.what(), 4 * kEchoChars));
  }
}

}  // namespace

nlohmann::json parseJson(std::istream& in, const std::string& what, const std::string& root) {
  return parse(in, what, root);
}
nlohmann::json parseJson(const std::string& text, const std::string& what, const std::string& root) {
  return parse(text, what, root);
}

}  // namespace collide::util
