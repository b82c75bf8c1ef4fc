#pragma once
// Seeds for randomized tests: COLLIDE_TEST_SEED=<n> overrides the default, and every
// test prints the seed it used so a failure can be replayed.
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include <gtest/gtest.h>

namespace collide::test {

inline std::uint64_t testSeed(std::uint64_t fallback) {
  std::uint64_t seed = fallback;
  if (const char* env = std::getenv("COLLIDE_TEST_SEED")) seed = std::stoull(env);
  std::cout << "[ seed     ] COLLIDE_TEST_SEED=" << seed << "\n";
  ::testing::Test::RecordProperty("seed", std::to_string(seed));
  return seed;
}

}  // namespace collide::test
