// The fp32 CPU collider (simd) against ODE's binary64 collider on the paper's diamond
// (hMax 10, dSph 0), side by side. The same bounds hold the rtl backend to ODE in
// test_afu.cpp (registered when an AFU preset is built): this checks the bounds are
// right for an fp32 collider that is known to be correct.
//
// At dSph = 0 in-layer neighbours touch exactly (d = 2r in real arithmetic), so binary32
// and binary64 disagree on some of them at the first step; every disagreement must be such
// a grazing pair. Measured (steps 0..5): 564 + 104 grazing disagreements at step 0 (gap
// <= 6e-17), none after, and the positions drift apart by at most 0.0035 m by step 5.
#include <gtest/gtest.h>

#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "support/lockstep.hpp"

using namespace collide;

namespace collide::test {
// The stated tolerances (also used for rtl vs ode).
constexpr long long kDiamondSteps = 6;        // the compressed phase (it flies apart at ~6)
constexpr double kGrazingTol = 1e-6;          // m: |d - (r1 + r2)| of a pair the two may disagree on
constexpr double kDiamondPosTol = 0.005;      // m: positions after kDiamondSteps steps
}  // namespace collide::test

TEST(Lockstep, SimdMatchesOdeOnTheDiamondUpToGrazingPairs) {
  auto sc = scene::loadScene(COLLIDE_REPO_SCENES "/diamond.json");
  SimdBackend simd;
  OdeBackend ode;
  const auto r = test::lockstep(sc, simd, ode, test::kDiamondSteps, test::kGrazingTol);
  std::size_t grazing = 0;
  for (std::size_t s = 0; s < r.size(); ++s) {
    EXPECT_EQ(r[s].pairsA, r[s].pairsB) << "step " << s;
    EXPECT_EQ(r[s].onlyA, r[s].onlyAGrazing) << "step " << s << ": simd-only contacts that are not grazing";
    EXPECT_EQ(r[s].onlyB, r[s].onlyBGrazing) << "step " << s << ": ode-only contacts that are not grazing";
    grazing += r[s].onlyA + r[s].onlyB;
  }
  EXPECT_GT(grazing, 0u) << "the diamond at dSph 0 has exactly touching pairs";
  EXPECT_LT(r.back().maxPosDiff, test::kDiamondPosTol);
  std::cout << "[ info     ] " << grazing << " grazing disagreements, positions within " << r.back().maxPosDiff
            << " m after " << r.size() << " steps\n";
}
