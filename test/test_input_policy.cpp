// One decision for bad pairs on every backend (collide/input_policy.hpp, docs/host.md "Bad
// pairs"): the same inputs through simd and ode (and rtl, test_afu.cpp) give the same hits
// and the same flags, and the good pairs among them are computed as usual.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "afu_contract.hpp"
#include "collide/input_policy.hpp"
#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "support/bad_pairs.hpp"

using namespace collide;

TEST(InputPolicy, EveryKindOfBadInputIsClassified) {
  const auto b = test::badPairs();
  for (std::size_t k = 0; k < b.pairs.size(); ++k)
    EXPECT_EQ(classifyPair(b.spheres, b.pairs.i[k], b.pairs.j[k]), b.want[k]) << "pair " << k << ": " << b.what[k];
}

TEST(InputPolicy, SimdAndOdeGiveTheSameDecisionAndFlagsOnBadPairs) {
  const auto b = test::badPairs();
  SimdBackend simd;
  OdeBackend ode;
  ContactSet cs, co;
  collidePairs(simd, b.spheres, b.pairs, cs);
  collidePairs(ode, b.spheres, b.pairs, co);  // no abort, no exception
  for (std::size_t k = 0; k < b.pairs.size(); ++k) {
    EXPECT_EQ(cs.hit[k], co.hit[k]) << "pair " << k << ": " << b.what[k];
    EXPECT_EQ(cs.flags[k], co.flags[k]) << "pair " << k << ": " << b.what[k];
    if (b.want[k] == PairInput::Ok) continue;
    EXPECT_EQ(cs.hit[k], 0) << b.what[k];
    EXPECT_EQ(cs.flags[k], b.want[k] == PairInput::NonFinite ? contract::REC_NONFINITE : contract::REC_HOST_RANGE)
        << b.what[k];
    EXPECT_EQ(cs.depth[k], 0.0) << b.what[k];
  }
  EXPECT_EQ(cs.hit[0], 1) << "the good pair is a contact";
}
