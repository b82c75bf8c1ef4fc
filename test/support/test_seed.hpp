#pragma once
// Seeds for randomized tests: COLLIDE_TEST_SEED=<n> overrides the default, and every
// test prints the seed it used so a failure can be replayed. COLLIDE_RUN_SEED (drawn anew by
// CI, printed by tools/test) is mixed into each test's default, so every run tries new cases.
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include <gtest/gtest.h>

namespace collide::test {

inline std::uint64_t testSeed(std::uint64_t fallback) {
  std::uint64_t seed = fallback;
  if (const char* run = std::getenv("COLLIDE_RUN_SEED"); run && *run) seed ^= std::stoull(run);
  if (const char* env = std::getenv("COLLIDE_TEST_SEED")) seed = std::stoull(env);
  std::cout << "[ seed     ] COLLIDE_TEST_SEED=" << seed << "\n";
  ::testing::Test::RecordProperty("seed", std::to_string(seed));
  return seed;
}

}  // namespace collide::test
