#pragma once
// World-mode contacts compared byte for byte (test only): simd's contacts (`collide spheres
// --backend simd`, world/cpu_world.hpp) as the reference, every column and the bad spheres.
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/spheres_csv.hpp"
#include "world/cpu_world.hpp"

namespace collide::test {

inline world::WorldContacts simdContacts(const SphereTable& t) {
  world::CpuWorld simd;
  world::WorldContacts w;
  world::WorldTiming time;
  simd.collide(t, w, time);
  return w;
}

template <typename T>
inline bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

inline void expectSame(const world::WorldContacts& want, const world::WorldContacts& got, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(want.pairs.size(), got.pairs.size());
  EXPECT_TRUE(sameBytes(want.pairs.i, got.pairs.i));
  EXPECT_TRUE(sameBytes(want.pairs.j, got.pairs.j));
  const auto &a = want.contacts, &b = got.contacts;
  EXPECT_EQ(a.format, b.format);
  EXPECT_TRUE(sameBytes(a.hit, b.hit));
  EXPECT_TRUE(sameBytes(a.flags, b.flags));
  for (auto col : {&ContactSet::px, &ContactSet::py, &ContactSet::pz, &ContactSet::nx, &ContactSet::ny,
                          &ContactSet::nz, &ContactSet::depth})
    EXPECT_TRUE(sameBytes(a.*col, b.*col));
  EXPECT_TRUE(sameBytes(want.badSpheres, got.badSpheres));
  EXPECT_TRUE(sameBytes(want.badFlags, got.badFlags));
}

inline std::string csvOf(const world::WorldContacts& w) {
  std::ostringstream s;
  cli::writeWorldContactsCsv(s, w);
  return s.str();
}

}  // namespace collide::test
