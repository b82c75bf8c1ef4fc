// driver::linkBoundNs is a lower bound on every preset, multi-channel ones included: no
// random batch of line reads and writes through the link model, and no driver run,
// finishes sooner than it says.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "driver/afu_driver.hpp"
#include "link/link_model.hpp"
#include "link/link_presets.hpp"
#include "support/model_afu.hpp"
#include "support/random_batch.hpp"
#include "support/test_seed.hpp"

using namespace collide;
using namespace collide::link;

namespace {

struct Shape {
  unsigned reads, writes;  // lines, including the first read and the status write
  double pRead, pWrite;    // chance of issuing, each cycle it is allowed
  unsigned window;         // outstanding requests the requester allows itself, each way
};

// A run shaped like an AFU call, on the link model alone: the host posts the driver's nine
// CSR writes (the last one starts the AFU); the requester then reads and writes lines as
// a random policy lets it, but no write before the first read's data is back (an AFU
// writes what it computed from what it read), and the status line last, once every read
// is answered and every other write acknowledged. It reacts in the cycle it sees a
// response, sooner than a registered AFU could: the bound must hold all the same.
// Returns the status cycle as the driver counts it.
std::uint64_t runShaped(const LinkParams& p, const Shape& s, std::uint64_t seed) {
  HostMemory mem;
  const auto buf = mem.allocate(64);
  LinkModel l(p, mem);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution issueRead(s.pRead), issueWrite(s.pWrite);
  for (std::uint8_t k = 1; k <= 9; ++k) l.hostWriteCsr(k, k);
  const std::uint32_t statusTag = 1u << 30;
  unsigned csrs = 0, readsIssued = 0, readsDone = 0, writesIssued = 0, writesDone = 0;
  bool statusSent = false;
  for (;;) {
    const LinkToAfu in = l.outputs();
    if (in.csr) ++csrs;
    if (in.rdResp) ++readsDone;
    if (in.wrResp) {
      if (in.wrResp->tag == statusTag) {
        l.tick({});
        return l.cycle();  // the cycle after the one that committed the status line
      }
      ++writesDone;
    }
    AfuToLink out;
    if (csrs == 9) {
      if (readsIssued < s.reads && readsIssued - readsDone < s.window && in.rdReqReady && issueRead(rng)) {
        out.rdReq = ReadReq{buf.base + readsIssued % 64, readsIssued};
        ++readsIssued;
      }
      const unsigned contacts = s.writes - 1;
      if (readsDone > 0 && in.wrReqReady) {
        if (writesIssued < contacts && writesIssued - writesDone < s.window && issueWrite(rng)) {
          out.wrReq = WriteReq{buf.base + writesIssued % 64, writesIssued, Line{}};
          ++writesIssued;
        } else if (!statusSent && readsDone == s.reads && writesDone == contacts) {
          out.wrReq = WriteReq{buf.base, statusTag, Line{}};
          statusSent = true;
        }
      }
    }
    l.tick(out);
  }
}

}  // namespace

TEST(LinkBound, NoRandomBatchThroughTheLinkModelBeatsTheBound) {
  const auto seed = test::testSeed(51);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<unsigned> lines(1, 2500), window(1, 64);
  std::uniform_real_distribution<double> chance(0.05, 1.0);
  for (const auto& preset : presets()) {
    SCOPED_TRACE(preset.name);
    // The shapes that press each term: all-out both ways, read-bound, write-bound, then random.
    std::vector<Shape> shapes = {{2500, 1500, 1, 1, 64}, {3000, 1, 1, 1, 64}, {1, 3000, 1, 1, 64}, {1, 1, 1, 1, 1}};
    for (int k = 0; k < 12; ++k) shapes.push_back({lines(rng), lines(rng), chance(rng), chance(rng), window(rng)});
    for (std::size_t k = 0; k < shapes.size(); ++k) {
      const Shape& s = shapes[k];
      LinkParams p = preset.params;
      p.seed = rng();
      const std::uint64_t status = runShaped(p, s, rng());
      const double modelled = driver::modelledRunNs(p, status);
      const double bound = driver::linkBoundNs(p, s.reads, s.writes);
      EXPECT_LE(bound, modelled) << "shape " << k << ": " << s.reads << " reads, " << s.writes << " writes, window "
                                 << s.window << ", p " << s.pRead << "/" << s.pWrite << ", status cycle " << status;
      // Not vacuous: the all-out shapes come within a few times the bound.
      if (k < 3) {
        EXPECT_LT(modelled, 3.0 * bound) << "shape " << k;
      }
    }
  }
}

TEST(LinkBound, NoDriverRunBeatsTheBoundOnAnyPreset) {
  const auto seed = test::testSeed(52);
  SphereTable t;
  PairList pairs;
  test::randomBatch(seed, 300, 3000, t, pairs);
  for (bool dense : {false, true}) {
    for (const auto& preset : presets()) {
      LinkParams p = preset.params;
      p.seed = seed;
      test::ModelAfu afu(test::ModelAfuConfig{});
      driver::DriverOptions o;
      o.dense = dense;
      driver::AfuDriver d(afu, p, o);
      const auto r = d.run(t, pairs);
      const auto& s = r.stats;
      EXPECT_EQ(s.linkBoundNs, driver::linkBoundNs(p, s.readLines, s.writeLines));
      EXPECT_LE(s.linkBoundNs, s.modelledNs) << preset.name << (dense ? " dense" : " compact");
      EXPECT_EQ(s.modelledNs, driver::modelledRunNs(p, s.statusCycle));
    }
  }
}

TEST(LinkBound, UsesTheAggregateBandwidthAndTheFastestChannel) {
  const LinkParams h = LinkParams::harp2();
  // 25 cycles (62.5 ns) for the QPI channel's 62 ns trip both ways; CSR 53 ns -> 21 cycles.
  const double fixed = h.transactionOverheadNs + 21 * 2.5 + h.pollNs + 2 * 25 * 2.5;
  EXPECT_DOUBLE_EQ(driver::linkBoundNs(h, 0, 0), fixed);
  EXPECT_DOUBLE_EQ(driver::linkBoundNs(h, 1000, 10), fixed + 1000 * 64.0 / 20.46);
  EXPECT_DOUBLE_EQ(driver::linkBoundNs(h, 10, 1000), fixed + 1000 * 64.0 / 20.52);
  // CXL's 64 GB/s is more than the 400 MHz port's line a cycle: the port sets the pace.
  const LinkParams c = LinkParams::cxl();
  EXPECT_DOUBLE_EQ(driver::linkBoundNs(c, 1000, 0) - driver::linkBoundNs(c, 0, 0), 1000 * 2.5);
  // On every preset the transfer term is the plain one: lines at the aggregate rate, capped
  // at the port (no slow-channel correction applies).
  for (const auto& preset : presets()) {
    const LinkParams& p = preset.params;
    auto perLine = [&](double gbps) { return std::max(gbps > 0 ? 64.0 / gbps : 0.0, p.cycleNs()); };
    const double base = driver::linkBoundNs(p, 0, 0);
    EXPECT_DOUBLE_EQ(driver::linkBoundNs(p, 5000, 1) - base, 5000 * perLine(p.aggregateReadGBps())) << preset.name;
    EXPECT_DOUBLE_EQ(driver::linkBoundNs(p, 1, 5000) - base, 5000 * perLine(p.aggregateWriteGBps())) << preset.name;
  }
}

TEST(LinkBound, SlowChannelsSetInAScenesStillNeverBeatIt) {
  // A line time beyond the driver's eight extra CSR cycles: the case the bound's
  // correction exists for (without it, a 0.4 GB/s channel beats the bound by a line).
  const auto seed = test::testSeed(53);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<unsigned> lines(1, 300), window(1, 64);
  LinkParams one = LinkParams::qpi();
  one.readGBps = 0.4;  // 32 cycles a line at 200 MHz
  one.writeGBps = 0.3;
  LinkParams four = LinkParams::qpi();
  four.setChannels({{"a", 0.5, 0.5, 200, 290, 200, 290}, {"b", 0.5, 0.5, 200, 290, 200, 290},
                    {"c", 0.5, 0.5, 200, 200, 200, 200}, {"d", 0.5, 0.5, 200, 200, 200, 200}});
  for (const auto& base : {one, four}) {
    std::vector<Shape> shapes = {{200, 1, 1, 1, 64}, {1, 200, 1, 1, 64}, {4, 1, 1, 1, 64}, {1, 4, 1, 1, 64}};
    for (int k = 0; k < 8; ++k) shapes.push_back({lines(rng), lines(rng), 1.0, 1.0, window(rng)});
    for (const Shape& s : shapes) {
      LinkParams p = base;
      p.seed = rng();
      const auto status = runShaped(p, s, rng());
      EXPECT_LE(driver::linkBoundNs(p, s.reads, s.writes), driver::modelledRunNs(p, status))
          << p.channels().size() << " channels, " << s.reads << " reads, " << s.writes << " writes";
    }
  }
}

