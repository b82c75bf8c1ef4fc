// The Verilator harness (driver/verilated_afu_port.hpp) against the hand-written TEST
// DOUBLE AFU (support/afu_test_double/CollideAfuTestDouble.sv), Verilated twice: with the
// io_idle/io_skipCycles ports (and FST tracing) and without them (only io_busy). The double
// answers every pair "separated", so the batches here never touch; what is checked is the
// plumbing: CSRs, 512-bit lines both ways (u16 lanes of pair lines, u32 fields of records
// and the status line), tags and reordering, back-pressure, reset, skipping, tracing.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "VAfuTestDouble.h"
#include "VAfuTestDoubleNoSkip.h"
#include "collide/rtl_backend.hpp"
#include "driver/afu_driver.hpp"
#include "driver/verilated_afu_port.hpp"
#include "support/test_seed.hpp"

using namespace collide;
using namespace collide::driver;

namespace {

using WithSkip = VerilatedAfuPort<VAfuTestDouble>;
using NoSkip = VerilatedAfuPort<VAfuTestDoubleNoSkip>;
static_assert(WithSkip::kHasIdle && WithSkip::kHasSkip && WithSkip::kHasBusy && WithSkip::kCanFst);
static_assert(!NoSkip::kHasIdle && !NoSkip::kHasSkip && NoSkip::kHasBusy && !NoSkip::kCanFst && !NoSkip::kCanVcd);

// Spheres on a line 1 apart, radius 0.1: no pair touches, whatever the indices.
void apartBatch(std::uint64_t seed, std::size_t spheres, std::size_t pairs, SphereTable& t, PairList& p) {
  t.clear();
  p.clear();
  for (std::size_t k = 0; k < spheres; ++k) t.push(static_cast<double>(k), 0.0, 0.0, 0.1);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::uint32_t> idx(0, static_cast<std::uint32_t>(spheres - 1));
  for (std::size_t k = 0; k < pairs; ++k) p.push(idx(rng), idx(rng));
}

DriverOptions test32() {
  DriverOptions o;
  o.format = LinkFormat::Binary32;
  o.maxSpheres = 1024;  // the double's MAX_SPHERES
  return o;
}

link::LinkParams qpi(std::uint64_t seed) {
  auto lp = link::LinkParams::qpi();
  lp.seed = seed;
  return lp;
}

template <class Port>
RunResult runOnce(const link::LinkParams& lp, const DriverOptions& o, const SphereTable& t, const PairList& p,
                  std::uint64_t* edges = nullptr) {
  Port port;
  AfuDriver d(port, lp, o);
  auto r = d.run(t, p);
  if (edges) *edges = port.cycle();
  return r;
}

bool sameStatus(const StatusLine& a, const StatusLine& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

template <class Port>
class VerilatedPort : public ::testing::Test {};
using Ports = ::testing::Types<WithSkip, NoSkip>;
TYPED_TEST_SUITE(VerilatedPort, Ports);

}  // namespace

TYPED_TEST(VerilatedPort, ResetLeavesTheAfuIdleAndQuiet) {
  TypeParam port;
  port.reset();
  EXPECT_TRUE(port.idle());
  port.setInputs(link::LinkToAfu{true, true, std::nullopt, std::nullopt, std::nullopt});
  const auto out = port.evalOutputs();
  EXPECT_FALSE(out.rdReq);
  EXPECT_FALSE(out.wrReq);
  port.clockEdge();
  EXPECT_TRUE(port.idle());
}

TYPED_TEST(VerilatedPort, CompactRunsAccountForEveryPairOverTheQpiLink) {
  const auto seed = test::testSeed(51);
  TypeParam port;
  AfuDriver d(port, qpi(seed), test32());
  SphereTable t;
  PairList p;
  for (std::size_t n : {0u, 1u, 15u, 16u, 17u, 1000u}) {  // the port is reused run after run
    apartBatch(seed + n, 300, n, t, p);
    const auto r = d.run(t, p);
    EXPECT_EQ(r.status.done, 1u);
    EXPECT_EQ(r.status.errors, 0u);
    EXPECT_EQ(r.status.pairsProcessed, n);
    EXPECT_EQ(r.status.contactsFound, 0u);
    EXPECT_EQ(r.status.recordsWritten, 0u);
    EXPECT_EQ(r.status.firstBadPair, 0xFFFFFFFFu);
    EXPECT_GE(r.status.cyclesLoading, 40u) << "300 spheres = 75 lines over QPI";
    EXPECT_EQ(r.status.cyclesComputing, (n + 15) / 16) << "one cycle per pair line";
    EXPECT_GT(r.status.cyclesWaitRead, 40u);
    EXPECT_GT(r.status.cyclesTotal, r.status.cyclesLoading);
    EXPECT_GT(r.stats.statusCycle, r.status.cyclesTotal);  // plus CSR and status-write latency
  }
  EXPECT_GT(d.link().stats().reorderedReadResponses, 0u) << "responses did come back out of order";
}

TYPED_TEST(VerilatedPort, DenseRecordsNameTheirPairsAndFlagBadIndices) {
  const auto seed = test::testSeed(52);
  std::mt19937_64 rng(seed);
  SphereTable t;
  PairList p;
  apartBatch(seed, 100, 333, t, p);
  // A bad index in every lane position across the lines: sphere i in some, sphere j in others.
  std::vector<std::size_t> bad;
  // Values that only a correct byte order keeps out of range (256 = 0x0100, 0x2300, ...).
  const std::uint32_t values[] = {256, 100, 0xFFFF, 0x2300, 0x0164, 0x8000, 0x1234};
  for (std::size_t k = 5, v = 0; k < p.size(); k += 17 + rng() % 9, ++v) {
    bad.push_back(k);
    (k % 2 ? p.i : p.j)[k] = v < 7 ? values[v] : 100 + static_cast<std::uint32_t>(rng() % 65436);
  }
  DriverOptions o = test32();
  o.dense = true;
  o.throwOnErrorFlags = false;
  TypeParam port;
  AfuDriver d(port, qpi(seed), o);
  const auto r = d.run(t, p);
  EXPECT_EQ(r.status.errors, contract::ERR_INDEX_RANGE);
  EXPECT_EQ(r.status.firstBadPair, bad.front());
  EXPECT_EQ(r.status.pairsProcessed, p.size());
  ASSERT_EQ(r.records.size(), p.size());
  std::size_t b = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const bool isBad = b < bad.size() && bad[b] == k;
    b += isBad;
    EXPECT_EQ(r.records[k].pair, k);
    EXPECT_FALSE(r.records[k].hit());
    EXPECT_EQ(r.records[k].recordCase(), isBad ? contract::KIND_INVALID : contract::KIND_SEPARATED) << "pair " << k;
  }
  // The default options turn the flag into an error naming the pair.
  TypeParam port2;
  AfuDriver strict(port2, link::LinkParams::ideal(), test32());
  try {
    strict.run(t, p);
    FAIL() << "no error";
  } catch (const AfuError& e) {
    EXPECT_NE(std::string(e.what()).find("first bad pair " + std::to_string(bad.front())), std::string::npos) << e.what();
  }
}

TYPED_TEST(VerilatedPort, TooManySpheresAndBadConfigurationAreFlagged) {
  SphereTable t;
  PairList p;
  apartBatch(1, 1100, 10, t, p);
  DriverOptions o = test32();
  o.maxSpheres = 4096;  // the driver believes a wrong manifest; the double flags it
  try {
    runOnce<TypeParam>(link::LinkParams::ideal(), o, t, p);
    FAIL() << "no error";
  } catch (const AfuError& e) {
    EXPECT_NE(std::string(e.what()).find("NUM_SPHERES above the on-chip table"), std::string::npos) << e.what();
    EXPECT_EQ(e.status.recordsWritten, 0u);
  }
}

TYPED_TEST(VerilatedPort, BackPressureAndSlowLinksChangeTimeNotResults) {
  const auto seed = test::testSeed(53);
  SphereTable t;
  PairList p;
  apartBatch(seed, 500, 3000, t, p);
  DriverOptions o = test32();
  o.dense = true;
  auto slow = qpi(seed);
  slow.readGBps = 0.4;   // about 1 line every 32 cycles: the read port is mostly busy
  slow.writeGBps = 0.3;  // and the write port back-pressures the double
  slow.maxWrites = 8;
  const auto a = runOnce<TypeParam>(slow, o, t, p);
  const auto b = runOnce<TypeParam>(link::LinkParams::ideal(), o, t, p);
  EXPECT_EQ(a.records.size(), b.records.size());
  EXPECT_EQ(a.status.pairsProcessed, b.status.pairsProcessed);
  EXPECT_GT(a.status.cyclesWaitWrite, 0u);
  EXPECT_GT(a.stats.statusCycle, 10 * b.stats.statusCycle);
}

// The requirement: jumping idle waits gives identical results and modelled time.
TYPED_TEST(VerilatedPort, SkippingIdleCyclesMatchesSteppingExactly) {
  const auto seed = test::testSeed(54);
  SphereTable t;
  PairList p;
  apartBatch(seed, 700, 5000, t, p);
  for (bool dense : {false, true}) {
    DriverOptions skip = test32(), step = test32();
    skip.dense = step.dense = dense;
    step.skipIdle = false;
    std::uint64_t skipEdges = 0, stepEdges = 0;
    const auto a = runOnce<TypeParam>(qpi(seed), skip, t, p, &skipEdges);
    const auto b = runOnce<TypeParam>(qpi(seed), step, t, p, &stepEdges);
    EXPECT_TRUE(sameStatus(a.status, b.status)) << "dense " << dense;
    EXPECT_EQ(a.stats.statusCycle, b.stats.statusCycle);
    EXPECT_EQ(a.stats.modelledNs, b.stats.modelledNs);
    ASSERT_EQ(a.records.size(), b.records.size());
    for (std::size_t k = 0; k < a.records.size(); ++k) {
      EXPECT_EQ(a.records[k].pair, b.records[k].pair);
      EXPECT_EQ(a.records[k].flags, b.records[k].flags);
    }
    EXPECT_EQ(b.stats.cyclesSkipped, 0u);
    EXPECT_GT(a.stats.cyclesSkipped, 0u) << "the CSR latency at least is skipped";
    if (TypeParam::kHasSkip) {
      // Dense mode reads one line at a time: mostly waiting, mostly skipped. (Measured with
      // seed 54: compact 16 %, dense 59 % of the cycles skipped.)
      EXPECT_GT(a.stats.cyclesSkipped, (dense ? 0.5 : 0.1) * a.stats.statusCycle) << "dense " << dense;
      EXPECT_LT(a.stats.cyclesStepped, (dense ? 0.5 : 0.9) * b.stats.cyclesStepped);
    }
    std::cout << "[ info     ] " << (TypeParam::kHasSkip ? "io_skipCycles" : "io_busy only") << (dense ? " dense" : " compact")
              << ": " << a.stats.statusCycle << " modelled cycles, " << a.stats.cyclesStepped << " stepped + "
              << a.stats.cyclesSkipped << " skipped (stepping all: " << b.stats.cyclesStepped << ")\n";
  }
}

TEST(VerilatedPortTrace, WritesAnFstOfTheRunWithSkippedTime) {
  const auto dir = std::filesystem::path(COLLIDE_TEST_WORK) / "trace";
  std::filesystem::create_directories(dir);
  const auto file = dir / "double.fst";
  std::filesystem::remove(file);
  SphereTable t;
  PairList p;
  apartBatch(5, 50, 200, t, p);
  {
    AfuPortOptions po;
    po.traceFile = file;
    WithSkip port(po);
    EXPECT_TRUE(port.tracing());
    AfuDriver d(port, qpi(5), test32());
    d.run(t, p);
  }  // closed by the destructor
  ASSERT_TRUE(std::filesystem::exists(file));
  EXPECT_GT(std::filesystem::file_size(file), 1000u);
}

TEST(VerilatedPortTrace, AskingForATraceTheModelCannotWriteIsAClearError) {
  AfuPortOptions po;
  po.traceFile = std::filesystem::path(COLLIDE_TEST_WORK) / "x.vcd";
  try {
    WithSkip port(po);
    FAIL() << "no error";
  } catch (const TraceUnavailable& e) {
    EXPECT_NE(std::string(e.what()).find("-DCOLLIDE_AFU_TRACE=VCD"), std::string::npos) << e.what();
  }
  po.traceFile = std::filesystem::path(COLLIDE_TEST_WORK) / "x.fst";
  EXPECT_THROW(NoSkip{po}, TraceUnavailable);
  po.traceFile = std::filesystem::path(COLLIDE_TEST_WORK) / "x.txt";
  EXPECT_THROW(WithSkip{po}, std::invalid_argument);
}

// The rtl backend splits batches larger than the AFU's sphere table into several runs.
TEST(VerilatedPortBackend, BigBatchesAreSplitIntoRunsThatFit) {
  const auto seed = test::testSeed(55);
  SphereTable t;
  PairList p;
  apartBatch(seed, 5000, 20000, t, p);
  RtlBackend rtl(std::make_unique<WithSkip>(), link::LinkParams::ideal(), test32());
  ContactSet out;
  rtl.collide(t, p, out);
  EXPECT_EQ(out.size(), p.size());
  EXPECT_EQ(out.hits(), 0u);
  EXPECT_GE(rtl.lastBatch().runs, 5u);
  EXPECT_EQ(rtl.lastBatch().counters.pairsProcessed, p.size());
  EXPECT_EQ(rtl.lastBatch().counters.done, rtl.lastBatch().runs);
  p.clear();
  rtl.collide(t, p, out);
  EXPECT_EQ(rtl.lastBatch().runs, 0u) << "an empty batch makes no AFU call";
}
