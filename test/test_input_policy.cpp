// One decision for bad pairs on every backend (collide/input_policy.hpp, docs/host.md "Bad
// pairs"): the same inputs through simd and ode (and rtl, test_afu.cpp) give the same
// decision and the same policy flags; a pair vector mode computes is computed as each
// backend's own arithmetic does it, over binary32's whole finite range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "afu_contract.hpp"
#include "collide/input_policy.hpp"
#include "collide/model_backend.hpp"
#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "support/bad_pairs.hpp"
#include "support/domain_pairs.hpp"
#include "support/test_seed.hpp"

using namespace collide;

namespace {
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Hit, the seven fields (bit for bit) and the flags of pair k in two contact sets; `ignore`
// masks flags only one of them can see.
void expectSame(const ContactSet& a, const ContactSet& b, std::size_t k, const std::string& what,
                std::uint8_t ignore = 0) {
  EXPECT_EQ(a.hit[k], b.hit[k]) << what;
  const std::vector<double>* ca[] = {&a.px, &a.py, &a.pz, &a.nx, &a.ny, &a.nz, &a.depth};
  const std::vector<double>* cb[] = {&b.px, &b.py, &b.pz, &b.nx, &b.ny, &b.nz, &b.depth};
  for (int f = 0; f < 7; ++f)
    EXPECT_TRUE(sameBits((*ca[f])[k], (*cb[f])[k])) << what << ", field " << f << ": " << (*ca[f])[k] << " vs "
                                                     << (*cb[f])[k];
  EXPECT_EQ(a.flags[k] & ~ignore, b.flags[k] & ~ignore) << what;
}
}  // namespace

TEST(InputPolicy, EveryKindOfBadInputIsClassified) {
  const auto b = test::badPairs();
  for (std::size_t k = 0; k < b.pairs.size(); ++k) {
    EXPECT_EQ(classifyPair(b.spheres, b.pairs.i[k], b.pairs.j[k]), b.want[k]) << "pair " << k << ": " << b.what[k];
    EXPECT_EQ(classifyVectorPair(b.spheres, b.pairs.i[k], b.pairs.j[k]), b.wantVector[k])
        << "pair " << k << ": " << b.what[k];
  }
}

TEST(InputPolicy, SimdAndOdeGiveTheSameDecisionAndFlagsOnBadPairs) {
  const auto b = test::badPairs();
  SimdBackend simd;
  OdeBackend ode;
  ContactSet cs, co;
  collidePairs(simd, b.spheres, b.pairs, cs);
  collidePairs(ode, b.spheres, b.pairs, co);  // no abort, no exception
  for (std::size_t k = 0; k < b.pairs.size(); ++k) {
    const std::string what = "pair " + std::to_string(k) + ": " + b.what[k];
    const VectorInput v = b.wantVector[k];
    const std::uint8_t policy = contract::REC_NONFINITE | contract::REC_HOST_RANGE;
    EXPECT_EQ(cs.flags[k] & policy, co.flags[k] & policy) << what;
    if (v == VectorInput::Ok) continue;
    if (v == VectorInput::OutsideScene) {  // computed, flagged
      EXPECT_NE(cs.flags[k] & contract::REC_HOST_RANGE, 0) << what;
      continue;
    }
    for (const ContactSet* c : {&cs, &co}) {
      EXPECT_EQ(c->hit[k], 0) << what;
      EXPECT_EQ(c->flags[k], v == VectorInput::NonFinite ? contract::REC_NONFINITE : contract::REC_HOST_RANGE)
          << what;
      EXPECT_EQ(c->depth[k], 0.0) << what;
    }
  }
  EXPECT_EQ(cs.hit[0], 1) << "the good pair is a contact";
  // Outside a scene's range but computed: both see the zero-radius pair at one centre as a
  // (coincident) contact, and both see the 2e6 m pair touch.
  for (std::size_t k = 0; k < b.pairs.size(); ++k)
    if (b.what[k].rfind("a zero radius", 0) == 0 || b.what[k].rfind("centres beyond", 0) == 0) {
      EXPECT_EQ(cs.hit[k], 1) << b.what[k];
      EXPECT_EQ(co.hit[k], 1) << b.what[k];
    }
}

// Vector mode over binary32's whole finite range (docs/host.md, "Bad pairs"): pairs at 1e7,
// 1e30 and subnormal scales are computed, never refused. simd gives the fp32 golden model's
// contacts bit for bit (the model also reports the SCPU's arithmetic exceptions, REC_ARITH,
// which the CPU cannot observe), and ODE gives simd64's. Pairs outside a scene's range carry
// REC_HOST_RANGE on every backend.
TEST(InputPolicy, VectorModeComputesEveryFinitePairAsTheGoldenModelDoes) {
  const std::uint64_t seed = test::testSeed(20261207);
  const auto d = test::domainPairs(seed);
  const SphereTable& s = d.spheres;
  const PairList& p = d.pairs;
  const std::vector<double>& scales = d.scale;
  SimdBackend simd, simd64(LinkFormat::Binary64);
  ModelBackend model("fp32");
  OdeBackend ode;
  ContactSet cs, cm, c64, co;
  collidePairs(simd, s, p, cs);
  collidePairs(model, s, p, cm);
  collidePairs(simd64, s, p, c64);
  collidePairs(ode, s, p, co);
  std::size_t hits = 0, outside = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const std::string what = "seed " + std::to_string(seed) + ", pair " + std::to_string(k) + " at scale " +
                             std::to_string(scales[k]);
    expectSame(cs, cm, k, what + " (simd vs model:fp32)", contract::REC_ARITH);
    expectSame(c64, co, k, what + " (simd64 vs ode)");
    EXPECT_EQ(cs.flags[k] & contract::REC_NONFINITE, 0) << what << ": finite inputs";
    const bool outsideScene = classifyVectorPair(s, p.i[k], p.j[k]) == VectorInput::OutsideScene;
    for (const ContactSet* c : {&cs, &cm, &c64, &co})
      EXPECT_EQ((c->flags[k] & contract::REC_HOST_RANGE) != 0, outsideScene) << what;
    hits += cs.hit[k];
    outside += outsideScene;
  }
  // The cases reach both answers and both sides of a scene's range.
  EXPECT_GT(hits, p.size() / 10);
  EXPECT_LT(hits, p.size() * 9 / 10);
  EXPECT_GT(outside, p.size() / 3);
  EXPECT_LT(outside, p.size());
}
