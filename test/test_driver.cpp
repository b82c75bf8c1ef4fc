// The AFU driver against the behavioural model AFU (support/model_afu): results, pair
// accounting, error flags, watchdog, and exact idle-cycle skipping end to end.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "driver/afu_driver.hpp"
#include "support/model_afu.hpp"
#include "support/random_batch.hpp"
#include "support/test_seed.hpp"

using namespace collide;
using namespace collide::driver;
using collide::test::ModelAfu;
using collide::test::ModelAfuConfig;

namespace {

using collide::test::randomBatch;

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expectSameContacts(const ContactSet& a, const ContactSet& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a.hit[k], b.hit[k]) << "pair " << k;
    const std::vector<double>* cols[2][7] = {{&a.px, &a.py, &a.pz, &a.nx, &a.ny, &a.nz, &a.depth},
                                            {&b.px, &b.py, &b.pz, &b.nx, &b.ny, &b.nz, &b.depth}};
    for (int c = 0; c < 7; ++c) ASSERT_TRUE(sameBits((*cols[0][c])[k], (*cols[1][c])[k])) << "pair " << k << " col " << c;
  }
}

struct Run {
  RunResult result;
  ContactSet contacts;
  std::uint64_t edges;
};

Run drive(const ModelAfuConfig& mc, const link::LinkParams& lp, DriverOptions o, const SphereTable& t,
          const PairList& p) {
  ModelAfu afu(mc);
  o.format = mc.format;
  AfuDriver d(afu, lp, o);
  Run r{d.run(t, p), {}, 0};
  r.contacts = d.toContactSet(r.result, p.size());
  r.edges = afu.edges();
  return r;
}

}  // namespace

TEST(Driver, Binary32RunMatchesTheSimdBackendBitForBit) {
  const auto seed = test::testSeed(31);
  SphereTable t;
  PairList p;
  randomBatch(seed, 300, 2000, t, p);
  ContactSet ref;
  SimdBackend().collide(t, p, ref);
  ASSERT_GT(ref.hits(), 50u);
  ASSERT_LT(ref.hits(), p.size());
  for (bool dense : {false, true}) {
    link::LinkParams lp = link::LinkParams::qpi();
    lp.seed = seed;
    DriverOptions o;
    o.dense = dense;
    const auto r = drive({}, lp, o, t, p);
    EXPECT_EQ(r.result.status.pairsProcessed, p.size());
    EXPECT_EQ(r.result.status.contactsFound, ref.hits());
    EXPECT_EQ(r.result.records.size(), dense ? p.size() : ref.hits());
    expectSameContacts(r.contacts, ref);
  }
}

TEST(Driver, Binary64RunMatchesOdeBitForBit) {
  const auto seed = test::testSeed(32);
  SphereTable t;
  PairList p;
  randomBatch(seed, 100, 500, t, p);
  ContactSet ref;
  OdeBackend().collide(t, p, ref);
  ModelAfuConfig mc;
  mc.format = LinkFormat::Binary64;
  const auto r = drive(mc, link::LinkParams::ideal(), {}, t, p);
  expectSameContacts(r.contacts, ref);
}

namespace {
// Skipping idle cycles changes nothing but the evaluations: same status, time and contacts.
void expectSkippingIsExact(link::LinkParams lp, std::uint64_t seed) {
  SphereTable t;
  PairList p;
  randomBatch(seed, 200, 3000, t, p);
  lp.seed = seed;
  DriverOptions skip, step;
  step.skipIdle = false;
  const auto a = drive({}, lp, skip, t, p);
  const auto b = drive({}, lp, step, t, p);
  EXPECT_EQ(a.result.stats.statusCycle, b.result.stats.statusCycle);
  EXPECT_EQ(a.result.stats.modelledNs, b.result.stats.modelledNs);
  EXPECT_EQ(std::memcmp(&a.result.status, &b.result.status, sizeof(StatusLine)), 0);
  EXPECT_EQ(a.result.status.cyclesWaitRead, b.result.status.cyclesWaitRead);
  expectSameContacts(a.contacts, b.contacts);
  EXPECT_EQ(b.result.stats.cyclesSkipped, 0u);
  EXPECT_GT(a.result.stats.cyclesSkipped, 0u);
  EXPECT_LT(a.edges, b.edges);  // and it saved evaluations
  std::cout << "[ info     ] " << lp.name << ": stepped " << b.edges << " edges, skipping " << a.edges
            << " edges, " << a.result.stats.statusCycle << " modelled cycles\n";
}
}  // namespace

TEST(Driver, SkippingIdleCyclesGivesIdenticalResultsAndTime) {
  expectSkippingIsExact(link::LinkParams::qpi(), test::testSeed(33));
}

TEST(Driver, SkippingIsExactOnAMultiChannelLinkToo) {
  expectSkippingIsExact(link::LinkParams::harp2(), test::testSeed(34));
}

TEST(Driver, AHungAfuIsAClearErrorNotAHang) {
  SphereTable t;
  PairList p;
  randomBatch(1, 10, 40, t, p);
  ModelAfuConfig mc;
  mc.hang = true;
  DriverOptions o;
  o.watchdogCycles = 100'000;
  try {
    drive(mc, link::LinkParams::qpi(), o, t, p);
    FAIL() << "no error";
  } catch (const AfuError& e) {
    EXPECT_NE(std::string(e.what()).find("AFU hung: no status line after 100000 cycles"), std::string::npos) << e.what();
  }
}

TEST(Driver, LostPairsAreAnError) {
  SphereTable t;
  PairList p;
  randomBatch(2, 10, 40, t, p);
  ModelAfuConfig mc;
  mc.losePair = true;
  try {
    drive(mc, link::LinkParams::ideal(), {}, t, p);
    FAIL() << "no error";
  } catch (const AfuError& e) {
    EXPECT_NE(std::string(e.what()).find("pairs processed 39 != pairs sent 40"), std::string::npos) << e.what();
  }
}

TEST(Driver, ErrorFlagsAreSurfaced) {
  SphereTable t;
  PairList p;
  randomBatch(3, 10, 40, t, p);
  p.i[17] = 12;  // fits u16, beyond NUM_SPHERES = 10
  try {
    drive({}, link::LinkParams::ideal(), {}, t, p);
    FAIL() << "no error";
  } catch (const AfuError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("sphere index out of range"), std::string::npos) << m;
    EXPECT_NE(m.find("first bad pair 17"), std::string::npos) << m;
    EXPECT_EQ(e.status.firstBadPair, 17u);
  }
  ModelAfuConfig small;
  small.maxSpheres = 4;
  DriverOptions o;
  o.maxSpheres = 100;  // the driver believes a wrong manifest; the AFU flags it
  try {
    drive(small, link::LinkParams::ideal(), o, t, p);
    FAIL() << "no error";
  } catch (const AfuError& e) {
    EXPECT_NE(std::string(e.what()).find("NUM_SPHERES above the on-chip table"), std::string::npos) << e.what();
  }
}

TEST(Driver, EmptyBatchAndModelledTime) {
  SphereTable t;
  PairList p;
  randomBatch(4, 5, 0, t, p);
  const auto ideal = drive({}, link::LinkParams::ideal(), {}, t, p);
  EXPECT_EQ(ideal.result.status.pairsProcessed, 0u);
  randomBatch(4, 5, 100, t, p);
  const auto i2 = drive({}, link::LinkParams::ideal(), {}, t, p);
  const auto q2 = drive({}, link::LinkParams::qpi(), {}, t, p);
  // qpi pays the 5 us transaction overhead and the latencies; ideal pays neither.
  EXPECT_LT(i2.result.stats.modelledNs, 1000.0);
  EXPECT_GT(q2.result.stats.modelledNs, 5000.0 + 3 * 200.0);
  EXPECT_GT(q2.result.stats.statusCycle, 5 * i2.result.stats.statusCycle);
}

TEST(Driver, TheLinkBoundCountsTheLinesMovedAndNeverExceedsTheModelledTime) {
  SphereTable t;
  PairList p;
  randomBatch(test::testSeed(97), 300, 2000, t, p);
  for (const auto& lp : {link::LinkParams::qpi(), link::LinkParams::ideal()}) {
    const auto r = drive(ModelAfuConfig{}, lp, DriverOptions{}, t, p);
    const auto& s = r.result.stats;
    // binary32: 4 spheres and 16 pairs a read line; 2 records a contact line, plus the status line
    EXPECT_EQ(s.readLines, (300 + 3) / 4 + (2000 + 15) / 16) << lp.name;
    EXPECT_EQ(s.writeLines, (r.result.status.recordsWritten + 1) / 2 + 1) << lp.name;
    EXPECT_DOUBLE_EQ(s.linkBoundNs, linkBoundNs(lp, s.readLines, s.writeLines));
    EXPECT_GT(s.linkBoundNs, 0.0);
    EXPECT_LE(s.linkBoundNs, s.modelledNs) << lp.name << ": the bound is above the modelled run";
  }
  // The formula itself: QPI writes at 5 GB/s are 12.8 ns a line; reads at 7 GB/s 9.14 ns.
  const auto q = link::LinkParams::qpi();
  const double fixed = q.transactionOverheadNs + q.csrWriteNs + q.pollNs + q.readLatencyMinNs + q.writeLatencyMinNs;
  EXPECT_DOUBLE_EQ(linkBoundNs(q, 10, 100), fixed + 100 * 12.8);
  EXPECT_DOUBLE_EQ(linkBoundNs(q, 1000, 100), fixed + 1000 * 64.0 / 7.0);
  // Ideal: one line a cycle each way, no per-call costs but a CSR and two 1-cycle trips.
  EXPECT_DOUBLE_EQ(linkBoundNs(link::LinkParams::ideal(), 7, 30), 3 * 5.0 + 30 * 5.0);
}

// A value that does not fit the link format is never silently a miss: every pair that uses
// the sphere carries REC_HOST_RANGE, whether the AFU called it a contact or not.
TEST(Driver, PairsWithInputsOutsideTheLinkFormatAreFlaggedNotDropped) {
  SphereTable t;
  t.push(0, 0, 0, 1);        // 0: fine
  t.push(1e39, 0, 0, 1);     // 1: x overflows binary32
  t.push(0.5, 0, 0, 1e-50);  // 2: a positive radius that rounds to zero in binary32
  t.push(0.5, 0, 0, 1);      // 3: fine, touches 0
  PairList p;
  p.push(0, 3); p.push(0, 1); p.push(0, 2); p.push(1, 2); p.push(3, 0);
  for (bool dense : {false, true}) {
    DriverOptions o;
    o.dense = dense;
    const auto r = drive({}, link::LinkParams::ideal(), o, t, p);
    EXPECT_EQ(r.result.rangePairs, (std::vector<std::uint32_t>{1, 2, 3})) << "dense " << dense;
    for (std::size_t k = 0; k < p.size(); ++k) {
      const bool bad = k >= 1 && k <= 3;
      EXPECT_EQ((r.contacts.flags[k] & contract::REC_HOST_RANGE) != 0, bad) << "pair " << k << " dense " << dense;
    }
    EXPECT_TRUE(r.contacts.hit[0] && r.contacts.hit[4]);
    EXPECT_FALSE(r.contacts.hit[1]);  // the AFU saw an infinity: no contact, but flagged
    // A flagged miss is a record in compact mode too, so its flag reaches the user either way.
    // Pairs 1 and 3 hold sphere 1's infinity.
    for (std::size_t k : {1, 3}) EXPECT_TRUE(r.contacts.flags[k] & contract::REC_NONFINITE) << k << " dense " << dense;
    EXPECT_EQ(r.result.status.flaggedMisses, 2u) << "dense " << dense;
    if (!dense) {
      EXPECT_EQ(r.result.records.size(), r.contacts.hits() + 2);
    }
  }
  // The same on the wire's own widths: writeSphereTable says which spheres did not fit.
  link::HostMemory m;
  const auto a = m.allocate(2);
  SphereTable h;
  h.push(70000, 0, 0, 1); h.push(1, 2, 3, 1e-9); h.push(1, 2, 3, 4); h.push(INFINITY, 0, 0, 1);
  EXPECT_EQ(writeSphereTable(m, a.base, h, LinkFormat::Binary16), (std::vector<std::uint8_t>{1, 1, 0, 0}));
  EXPECT_EQ(writeSphereTable(m, a.base, h, LinkFormat::BFloat16), (std::vector<std::uint8_t>{0, 0, 0, 0}));
}
