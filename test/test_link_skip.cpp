// Cycle skipping on the link model alone: jumping idle cycles with nextEventCycle()
// gives exactly the cycles, responses and order of ticking every cycle.
#include <gtest/gtest.h>

#include "link/link_model.hpp"
#include "support/link_harness.hpp"
#include "support/test_seed.hpp"

using namespace collide;
using namespace collide::link;
using collide::test::runTraffic;

namespace {
void expectSameRun(const LinkParams& p, unsigned n, unsigned burst, bool writes, double minSkipped) {
  HostMemory mem;
  const auto b = mem.allocate(16);
  LinkModel stepped(p, mem), skipped(p, mem);
  const auto a = runTraffic(stepped, b.base, n, burst, writes, false);
  const auto s = runTraffic(skipped, b.base, n, burst, writes, true);
  EXPECT_EQ(stepped.cycle(), skipped.cycle());
  EXPECT_EQ(a.accepted, s.accepted);
  EXPECT_EQ(a.readResp, s.readResp);
  EXPECT_EQ(a.writeResp, s.writeResp);
  EXPECT_EQ(stepped.stats().cyclesSkipped, 0u);
  // The skipping run really skipped: otherwise this test proves nothing.
  EXPECT_GT(static_cast<double>(skipped.stats().cyclesSkipped), minSkipped * stepped.cycle()) << "burst " << burst;
}
}  // namespace

TEST(LinkSkip, SkippingMatchesSteppingForReadBursts) {
  LinkParams p = LinkParams::qpi();
  p.seed = test::testSeed(21);
  expectSameRun(p, 600, 1, false, 0.9);  // one at a time: almost all waiting
  expectSameRun(p, 600, 5, false, 0.5);
  expectSameRun(p, 600, 64, false, 0.1);
}

TEST(LinkSkip, SkippingMatchesSteppingForWriteBursts) {
  LinkParams p = LinkParams::qpi();
  p.seed = test::testSeed(22);
  expectSameRun(p, 600, 1, true, 0.9);
  expectSameRun(p, 600, 7, true, 0.5);
  expectSameRun(p, 600, 64, true, 0.1);
}

TEST(LinkSkip, SkippingMatchesSteppingInOrderAndSlow) {
  LinkParams p = LinkParams::qpi();
  p.seed = test::testSeed(23);
  p.reorder = false;
  p.readGBps = 0.5;  // bandwidth-bound: port-free times, not due times, set the events
  expectSameRun(p, 300, 16, false, 0.1);
}

// Several channels: per-channel response ports and latencies set the events.
TEST(LinkSkip, SkippingMatchesSteppingOnAMultiChannelLink) {
  LinkParams p = LinkParams::harp2();
  p.seed = test::testSeed(25);
  for (bool writes : {false, true}) {
    expectSameRun(p, 600, 1, writes, 0.9);
    expectSameRun(p, 600, 5, writes, 0.5);
    expectSameRun(p, 600, 64, writes, 0.1);
  }
  // In order and bandwidth-bound on every channel: port-free times on different
  // channels, not due times, decide when the oldest response may go.
  p.reorder = false;
  p.moreChannels[0].readGBps = 0.5;
  p.readGBps = p.moreChannels[1].readGBps = 1.0;
  expectSameRun(p, 300, 16, false, 0.1);
}

TEST(LinkSkip, NextEventIsTheFirstCycleWithAnEvent) {
  HostMemory mem;
  const auto b = mem.allocate(1);
  LinkParams p = LinkParams::qpi();
  p.seed = test::testSeed(24);
  LinkModel l(p, mem);
  EXPECT_EQ(l.nextEventCycle(), LinkModel::kNever);
  l.tick({ReadReq{b.base, 0}, std::nullopt});
  const auto next = l.nextEventCycle();
  ASSERT_NE(next, LinkModel::kNever);
  while (l.cycle() < next) {
    EXPECT_FALSE(l.outputs().anyEvent()) << "event before nextEventCycle at " << l.cycle();
    l.tick({});
  }
  EXPECT_TRUE(l.outputs().rdResp);
}

TEST(LinkSkip, SkippingPastAnEventIsRefused) {
  HostMemory mem;
  const auto b = mem.allocate(1);
  LinkModel l(LinkParams::qpi(), mem);
  l.tick({ReadReq{b.base, 0}, std::nullopt});
  EXPECT_THROW(l.skipTo(l.nextEventCycle() + 1), std::logic_error);
  EXPECT_NO_THROW(l.skipTo(l.nextEventCycle()));
}
