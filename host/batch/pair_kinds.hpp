#pragma once
// The pair kinds (docs/pair-kinds.md) by the names the generator's manifest (afu.pairKinds),
// scenes (collision.require) and `collide pairs --kind` use. Sphere/sphere is every backend's
// and every AFU's; the others have CPU references (host/pairs) and units not yet on an AFU.
#include <array>
#include <string>

namespace collide {

inline constexpr std::array<const char*, 3> kPairKinds = {"sphere-sphere", "sphere-plane", "capsule-sphere"};

inline bool isPairKind(const std::string& name) {
  for (const char* k : kPairKinds)
    if (name == k) return true;
  return false;
}

// "sphere-sphere, sphere-plane or capsule-sphere", for messages.
inline std::string pairKindList() {
  std::string s;
  for (std::size_t i = 0; i < kPairKinds.size(); ++i)
    s += (i == 0 ? "" : i + 1 == kPairKinds.size() ? " or " : ", ") + std::string(kPairKinds[i]);
  return s;
}

}  // namespace collide
