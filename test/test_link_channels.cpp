// Several physical channels behind the AFU port: requests spread over them by port
// availability (eVC_VA-style), each channel with its own bandwidth and latency, the port
// still one line a cycle. Timing is compared as ratios within one run of the model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "link/link_model.hpp"
#include "link/link_presets.hpp"
#include "support/link_harness.hpp"
#include "support/test_seed.hpp"

using namespace collide;
using namespace collide::link;
using collide::test::runTraffic;

namespace {

// 200 MHz, 3.2 GB/s a channel: 4 cycles a line, so one channel is far below the port's
// line a cycle and two are still below it. Short fixed latency: bandwidth binds.
ChannelParams slowChannel(const char* name) { return {name, 3.2, 3.2, 50.0, 50.0, 50.0, 50.0}; }

LinkParams withChannels(std::vector<ChannelParams> chans, std::uint64_t seed) {
  LinkParams p = LinkParams::qpi();
  p.setChannels(chans);
  p.seed = seed;
  return p;
}

double span(const std::vector<test::Event>& e) { return static_cast<double>(e.back().cycle - e.front().cycle); }

}  // namespace

TEST(LinkChannels, TwoEqualChannelsHalveALongWriteBurst) {
  const auto seed = test::testSeed(41);
  HostMemory mem;
  const auto b = mem.allocate(16);
  LinkModel one(withChannels({slowChannel("a")}, seed), mem);
  LinkModel two(withChannels({slowChannel("a"), slowChannel("b")}, seed), mem);
  const unsigned n = 2000;
  const auto t1 = runTraffic(one, b.base, n, n, true, false);
  const auto t2 = runTraffic(two, b.base, n, n, true, false);
  const double ratio = span(t2.accepted) / span(t1.accepted);
  EXPECT_NEAR(ratio, 0.5, 0.01) << "one channel " << span(t1.accepted) << " cycles, two " << span(t2.accepted);
  // Equal channels: the tie rule alternates them.
  const auto& w = two.stats().writesByChannel;
  ASSERT_EQ(w.size(), 2u);
  EXPECT_LE(std::max(w[0], w[1]) - std::min(w[0], w[1]), 1u);
  EXPECT_EQ(one.stats().writesByChannel, std::vector<std::uint64_t>{n});
}

TEST(LinkChannels, TwoEqualChannelsHalveALongReadBurst) {
  const auto seed = test::testSeed(42);
  HostMemory mem;
  const auto b = mem.allocate(16);
  LinkModel one(withChannels({slowChannel("a")}, seed), mem);
  LinkModel two(withChannels({slowChannel("a"), slowChannel("b")}, seed), mem);
  const unsigned n = 2000;
  const auto t1 = runTraffic(one, b.base, n, n, false, false);
  const auto t2 = runTraffic(two, b.base, n, n, false, false);
  EXPECT_NEAR(span(t2.readResp) / span(t1.readResp), 0.5, 0.01);
  const auto& r = two.stats().readsByChannel;
  EXPECT_LE(std::max(r[0], r[1]) - std::min(r[0], r[1]), 1u);
}

TEST(LinkChannels, UnequalChannelsShareByBandwidth) {
  const auto seed = test::testSeed(43);
  HostMemory mem;
  const auto b = mem.allocate(16);
  ChannelParams fast = slowChannel("fast");
  fast.readGBps = fast.writeGBps = 6.4;  // 2 cycles a line against the other's 4
  for (bool writes : {true, false}) {
    LinkModel l(withChannels({slowChannel("slow"), fast}, seed), mem);
    const unsigned n = 3000;
    const auto t = runTraffic(l, b.base, n, n, writes, false);
    const auto& by = writes ? l.stats().writesByChannel : l.stats().readsByChannel;
    // 1/4 + 1/2 lines a cycle: the fast channel carries two thirds.
    EXPECT_NEAR(static_cast<double>(by[1]) / n, 2.0 / 3.0, 0.01) << (writes ? "writes" : "reads");
    // ...and together they move 0.75 lines a cycle.
    EXPECT_NEAR(n / span(writes ? t.accepted : t.readResp), 0.75, 0.01) << (writes ? "writes" : "reads");
  }
}

TEST(LinkChannels, TheAfuPortStaysOneLineACycle) {
  // Four 6.4 GB/s channels at 200 MHz could carry 25.6 GB/s; the port carries 12.8.
  HostMemory mem;
  const auto b = mem.allocate(16);
  std::vector<ChannelParams> four;
  for (const char* name : {"a", "b", "c", "d"}) four.push_back({name, 6.4, 6.4, 20.0, 20.0, 20.0, 20.0});
  LinkParams p = withChannels(four, test::testSeed(44));
  p.reorder = false;
  for (bool writes : {true, false}) {
    LinkModel l(p, mem);
    const unsigned n = 1000;
    const auto t = runTraffic(l, b.base, n, n, writes, false);
    const auto& e = writes ? t.accepted : t.readResp;
    for (std::size_t k = 1; k < e.size(); ++k) ASSERT_GT(e[k].cycle, e[k - 1].cycle) << "two lines in one cycle";
    EXPECT_EQ(span(e), n - 1.0) << "back to back at the port";
  }
}

TEST(LinkChannels, IdleChannelsTieToTheLowestIndex) {
  HostMemory mem;
  const auto b = mem.allocate(4);
  LinkModel l(withChannels({slowChannel("a"), slowChannel("b"), slowChannel("c")}, test::testSeed(45)), mem);
  // All idle: channel 0. Next cycle channel 0 is still busy (4 cycles a line): channel 1.
  l.tick({std::nullopt, WriteReq{b.base, 0, Line{}}});
  EXPECT_EQ(l.stats().writesByChannel, (std::vector<std::uint64_t>{1, 0, 0}));
  l.tick({std::nullopt, WriteReq{b.base, 1, Line{}}});
  EXPECT_EQ(l.stats().writesByChannel, (std::vector<std::uint64_t>{1, 1, 0}));
  // After a pause longer than a line time every channel is free again: channel 0.
  while (l.writesOutstanding()) l.tick({});
  for (int k = 0; k < 8; ++k) l.tick({});
  l.tick({std::nullopt, WriteReq{b.base, 2, Line{}}});
  EXPECT_EQ(l.stats().writesByChannel, (std::vector<std::uint64_t>{2, 1, 0}));
}

TEST(LinkChannels, EachChannelDrawsItsOwnLatency) {
  // HARP v2: QPI 62-150 ns (25-60 cycles at 400 MHz), PCIe 400-600 ns (160-240 cycles).
  HostMemory mem;
  const auto b = mem.allocate(16);
  LinkParams p = LinkParams::harp2();
  p.seed = test::testSeed(46);
  LinkModel l(p, mem);
  const auto t = runTraffic(l, b.base, 900, 3, false, false);  // bursts of 3: one a channel
  unsigned fast = 0, slow = 0;
  for (const auto& r : t.readResp) {
    const auto lat = r.cycle - t.acceptCycle.at(r.tag);
    // +1: two PCIe reads due in one cycle leave one a cycle, the port's limit.
    const bool inQpi = lat >= 25 && lat <= 60, inPcie = lat >= 160 && lat <= 241;
    ASSERT_TRUE(inQpi || inPcie) << "tag " << r.tag << " latency " << lat;
    (inQpi ? fast : slow) += 1;
  }
  const auto& by = l.stats().readsByChannel;
  EXPECT_EQ(fast, by[0]);
  EXPECT_EQ(slow, by[1] + by[2]);
  EXPECT_GT(by[1], 0u);
  EXPECT_GT(by[2], 0u);
}

TEST(LinkChannels, LongBurstsOnEachPresetSustainWhatTheDocsSay) {
  // docs/host.md: qpi and pac reach their bandwidth; on harp2 and cxl the AFU's 64 tags
  // over their round trips bind first, at about 12 GB/s.
  const auto seed = test::testSeed(47);
  struct Want { const char* name; double lo, hi; };
  for (const Want& w : {Want{"qpi", 0, 0}, Want{"pac", 0, 0}, Want{"harp2", 11.5, 13.0}, Want{"cxl", 10.5, 12.5}}) {
    for (bool writes : {false, true}) {
      LinkParams p = presetParams(w.name);
      p.seed = seed;
      HostMemory mem;
      const auto b = mem.allocate(16);
      LinkModel l(p, mem);
      const unsigned n = 10000;
      const auto t = runTraffic(l, b.base, n, n, writes, false);
      const double gbps = n * 64.0 / (span(writes ? t.accepted : t.readResp) * p.cycleNs());
      const double agg = writes ? p.aggregateWriteGBps() : p.aggregateReadGBps();
      SCOPED_TRACE(std::string(w.name) + (writes ? " writes" : " reads"));
      if (w.hi == 0) {
        EXPECT_NEAR(gbps, agg, 0.01 * agg);
      } else {
        EXPECT_GT(gbps, w.lo);
        EXPECT_LT(gbps, w.hi);
        EXPECT_LT(gbps, 0.7 * agg);
      }
    }
  }
}
