#pragma once
// One contact of a pair kind's CPU reference (docs/pair-kinds.md), in T = float or double:
// every field zero when there is none.

namespace collide::pairs {

template <typename T>
struct Contact {
  bool hit = false;
  T pos[3] = {0, 0, 0};
  T normal[3] = {0, 0, 0};
  T depth = 0;
};

}  // namespace collide::pairs
