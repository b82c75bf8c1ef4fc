#pragma once
// What every fuzz target checks: the parser under test either accepts the input or refuses
// it with an error of the type its header documents, whose message starts with the name
// the input was given ("fuzz-input: ...") or the key path the parser reports ("scene.link:
// ..."), so a user can see which file or key was wrong. Any
// other exception escapes the target and libFuzzer (or the replay driver) reports it as a
// crash; ASan and UBSan report memory and arithmetic faults.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace collide::fuzz {

inline constexpr const char* kInputName = "fuzz-input";

// Aborts, printing the message, when `what` does not start with `prefix`.
inline void requireNamed(const char* kind, const std::string& what, const std::string& prefix = kInputName) {
  if (what.compare(0, prefix.size(), prefix) != 0) {
    std::fprintf(stderr, "%s does not name the input (\"%s\" expected first): %s\n", kind, prefix.c_str(),
                 what.c_str());
    std::abort();
  }
}

}  // namespace collide::fuzz
