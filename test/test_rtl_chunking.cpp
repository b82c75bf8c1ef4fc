// The rtl backend's batch splitting, checked with the behavioural model AFU (which computes
// the binary32 formula): a batch whose spheres exceed the AFU's table is split into runs
// and gives the simd backend's results bit for bit, in pair order.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "collide/rtl_backend.hpp"
#include "collide/simd_backend.hpp"
#include "support/model_afu.hpp"
#include "support/random_batch.hpp"
#include "support/test_seed.hpp"

using namespace collide;

TEST(RtlChunking, BatchesBeyondTheSphereTableAreSplitAndMatchSimd) {
  const auto seed = test::testSeed(61);
  SphereTable t;
  PairList p;
  test::randomBatch(seed, 700, 4000, t, p, {1.5, 0.1, 0.6});

  test::ModelAfuConfig mc;
  mc.maxSpheres = 64;  // 700 spheres: at least 11 runs
  driver::DriverOptions o;
  o.maxSpheres = 64;
  RtlBackend rtl(std::make_unique<test::ModelAfu>(mc), link::LinkParams::ideal(), o);
  ContactSet got, want;
  rtl.collide(t, p, got);
  SimdBackend().collide(t, p, want);
  ASSERT_GT(want.hits(), 100u);
  EXPECT_GE(rtl.lastBatch().runs, 11u);
  EXPECT_EQ(rtl.lastBatch().counters.pairsProcessed, p.size());
  EXPECT_EQ(rtl.lastBatch().counters.contactsFound, want.hits());
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 0; k < p.size(); ++k) {
    ASSERT_EQ(got.hit[k], want.hit[k]) << "pair " << k;
    const double a[7] = {got.px[k], got.py[k], got.pz[k], got.nx[k], got.ny[k], got.nz[k], got.depth[k]};
    const double b[7] = {want.px[k], want.py[k], want.pz[k], want.nx[k], want.ny[k], want.nz[k], want.depth[k]};
    ASSERT_EQ(std::memcmp(a, b, sizeof a), 0) << "pair " << k;
  }
}
