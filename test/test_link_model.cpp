// Link model behaviour: latency range, bandwidth, outstanding limits, reordering, ideal.
#include <gtest/gtest.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "link/link_model.hpp"
#include "support/link_harness.hpp"
#include "support/test_seed.hpp"

using namespace collide;
using namespace collide::link;
using collide::test::runTraffic;

namespace {
struct Fixture {
  HostMemory mem;
  Buffer buf = mem.allocate(16);
};
}  // namespace

TEST(LinkModel, ReadLatencyStaysInTheConfiguredRange) {
  Fixture f;
  LinkParams p = LinkParams::qpi();
  p.seed = test::testSeed(11);
  LinkModel l(p, f.mem);
  // One request in flight at a time: the round trip is the drawn latency.
  const auto t = runTraffic(l, f.buf.base, 500, 1, false, false);
  const std::uint64_t lo = p.nsToCycles(200), hi = p.nsToCycles(290);
  EXPECT_EQ(lo, 40u);
  EXPECT_EQ(hi, 58u);
  std::uint64_t seenLo = ~0ull, seenHi = 0;
  for (const auto& r : t.readResp) {
    const auto lat = r.cycle - t.acceptCycle.at(r.tag);
    ASSERT_GE(lat, lo) << "tag " << r.tag;
    ASSERT_LE(lat, hi) << "tag " << r.tag;
    seenLo = std::min(seenLo, lat);
    seenHi = std::max(seenHi, lat);
  }
  // Drawn, not constant: 500 draws over 19 values cover both ends of the range.
  EXPECT_EQ(seenLo, lo);
  EXPECT_EQ(seenHi, hi);
}

TEST(LinkModel, ReadBandwidthLimitHolds) {
  Fixture f;
  LinkParams p = LinkParams::qpi();
  p.seed = test::testSeed(12);
  LinkModel l(p, f.mem);
  const unsigned n = 3000;
  const auto t = runTraffic(l, f.buf.base, n, n, false, false);
  ASSERT_EQ(t.readResp.size(), n);
  // Bytes delivered in any window of W cycles stay within W * 35 B/cycle (7 GB/s at
  // 200 MHz) plus one line of slack for the window edges.
  const double bytesPerCycle = p.readGBps * 1e9 / (p.clockMHz * 1e6);
  for (std::size_t a = 0; a < n; a += 97)
    for (std::size_t b = a + 1; b < n; b += 131) {
      const double w = static_cast<double>(t.readResp[b].cycle - t.readResp[a].cycle + 1);
      ASSERT_LE((b - a + 1) * 64.0, w * bytesPerCycle + 64.0) << "responses " << a << ".." << b;
    }
  // ...and the link is bandwidth-bound here (64 outstanding x 64 B / ~49 cycles > 35 B/cycle),
  // so the achieved rate is close to the limit: the test would catch a too-slow model too.
  const double achieved = n * 64.0 / static_cast<double>(t.readResp.back().cycle - t.readResp.front().cycle);
  EXPECT_GT(achieved, 0.95 * bytesPerCycle);
  EXPECT_LE(achieved, bytesPerCycle * 1.001);
}

TEST(LinkModel, WriteBandwidthLimitHolds) {
  Fixture f;
  LinkParams p = LinkParams::qpi();
  p.seed = test::testSeed(13);
  LinkModel l(p, f.mem);
  const unsigned n = 2000;
  const auto t = runTraffic(l, f.buf.base, n, n, true, false);
  const double bytesPerCycle = p.writeGBps * 1e9 / (p.clockMHz * 1e6);
  const double achieved = n * 64.0 / static_cast<double>(t.accepted.back().cycle - t.accepted.front().cycle);
  EXPECT_LE(achieved, bytesPerCycle * 1.001);
  EXPECT_GT(achieved, 0.95 * bytesPerCycle);
}

TEST(LinkModel, OutstandingLimitsAreNeverExceeded) {
  Fixture f;
  for (unsigned limit : {64u, 8u, 1u}) {
    LinkParams p = LinkParams::qpi();
    p.maxReads = p.maxWrites = limit;
    p.readGBps = p.writeGBps = 0;  // not bandwidth-bound...
    // ...and latency (100-120 cycles) above every limit, so the limit is what binds.
    p.readLatencyMinNs = p.writeLatencyMinNs = 500;
    p.readLatencyMaxNs = p.writeLatencyMaxNs = 600;
    p.seed = test::testSeed(14);
    LinkModel l(p, f.mem);
    runTraffic(l, f.buf.base, 1000, 1000, false, false);
    EXPECT_EQ(l.stats().maxReadsOutstanding, limit);
    LinkModel w(p, f.mem);
    runTraffic(w, f.buf.base, 1000, 1000, true, false);
    EXPECT_EQ(w.stats().maxWritesOutstanding, limit);
  }
}

TEST(LinkModel, RequestWithoutReadyIsNotTaken) {
  Fixture f;
  LinkParams p = LinkParams::qpi();
  p.maxReads = 2;
  LinkModel l(p, f.mem);
  l.tick({ReadReq{f.buf.base, 0}, std::nullopt});
  l.tick({ReadReq{f.buf.base, 1}, std::nullopt});
  EXPECT_FALSE(l.outputs().rdReqReady);
  l.tick({ReadReq{f.buf.base, 2}, std::nullopt});  // back-pressure: held off, not an error
  EXPECT_EQ(l.readsOutstanding(), 2u);
  EXPECT_EQ(l.stats().readsAccepted, 2u);
}

TEST(LinkModel, DuplicateTagAndBadAddressAreProtocolErrors) {
  Fixture f;
  LinkModel l(LinkParams::qpi(), f.mem);
  l.tick({ReadReq{f.buf.base, 5}, std::nullopt});
  EXPECT_THROW(l.tick({ReadReq{f.buf.base, 5}, std::nullopt}), LinkProtocolError);
  LinkModel m(LinkParams::qpi(), f.mem);
  EXPECT_THROW(m.tick({ReadReq{0, 1}, std::nullopt}), LinkProtocolError);
  EXPECT_THROW(m.tick({ReadReq{f.mem.sizeLines(), 1}, std::nullopt}), LinkProtocolError);
}

TEST(LinkModel, ReordersOnlyWhenReorderingIsOn) {
  Fixture f;
  const auto seed = test::testSeed(15);
  for (bool reorder : {true, false}) {
    LinkParams p = LinkParams::qpi();
    p.reorder = reorder;
    p.seed = seed;
    LinkModel l(p, f.mem);
    const auto t = runTraffic(l, f.buf.base, 2000, 2000, false, false);
    std::size_t outOfOrder = 0;
    for (std::size_t k = 1; k < t.readResp.size(); ++k) outOfOrder += t.readResp[k].tag < t.readResp[k - 1].tag;
    if (reorder) {
      EXPECT_GT(outOfOrder, 100u);
      EXPECT_GT(l.stats().reorderedReadResponses, 100u);
    } else {
      EXPECT_EQ(outOfOrder, 0u);
      EXPECT_EQ(l.stats().reorderedReadResponses, 0u);
    }
  }
}

TEST(LinkModel, IdealLinkAnswersInOneCycle) {
  Fixture f;
  LinkModel l(LinkParams::ideal(), f.mem);
  const auto t = runTraffic(l, f.buf.base, 200, 200, false, false);
  for (const auto& r : t.readResp) ASSERT_EQ(r.cycle - t.acceptCycle.at(r.tag), 1u);
  // One line per cycle sustained: 200 reads in 201 cycles.
  EXPECT_EQ(t.readResp.back().cycle, 200u);
  LinkModel w(LinkParams::ideal(), f.mem);
  const auto tw = runTraffic(w, f.buf.base, 200, 200, true, false);
  for (const auto& r : tw.writeResp) ASSERT_EQ(r.cycle - tw.acceptCycle.at(r.tag), 1u);
  LinkModel c(LinkParams::ideal(), f.mem);
  c.hostWriteCsr(3, 42);
  EXPECT_FALSE(c.outputs().csr);
  c.tick({});
  ASSERT_TRUE(c.outputs().csr);
  EXPECT_EQ(c.outputs().csr->index, 3);
  EXPECT_EQ(c.outputs().csr->data, 42u);
}

TEST(LinkModel, ReadsSeeMemoryAndWritesLandWhenAcknowledged) {
  HostMemory mem;
  const auto b = mem.allocate(2);
  mem.store<std::uint32_t>(b.base, 0, 0xdeadbeef);
  LinkModel l(LinkParams::ideal(), mem);
  l.tick({ReadReq{b.base, 1}, std::nullopt});
  ASSERT_TRUE(l.outputs().rdResp);
  EXPECT_EQ(l.outputs().rdResp->data[0], 0xef);
  Line data{};
  data[63] = 7;
  LinkParams slow = LinkParams::ideal();
  slow.writeLatencyMinNs = slow.writeLatencyMaxNs = 50;  // 10 cycles
  LinkModel w(slow, mem);
  w.tick({std::nullopt, WriteReq{b.base + 1, 0, data}});
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(mem.line(b.base + 1)[63], 0) << "cycle " << w.cycle();
    EXPECT_FALSE(w.outputs().wrResp);
    w.tick({});
  }
  ASSERT_TRUE(w.outputs().wrResp);
  w.tick({});
  EXPECT_EQ(mem.line(b.base + 1)[63], 7);
}

TEST(LinkModel, CsrWritesArriveInOrderAfterTheirLatency) {
  HostMemory mem;
  LinkParams p = LinkParams::qpi();
  LinkModel l(p, mem);
  for (std::uint8_t k = 0; k < 4; ++k) l.hostWriteCsr(k, 100 + k);
  const auto lat = p.nsToCycles(p.csrWriteNs);
  std::vector<std::pair<std::uint64_t, std::uint8_t>> seen;
  while (seen.size() < 4) {
    if (auto c = l.outputs().csr) seen.emplace_back(l.cycle(), c->index);
    l.tick({});
  }
  for (std::uint8_t k = 0; k < 4; ++k) {
    EXPECT_EQ(seen[k].second, k);
    EXPECT_EQ(seen[k].first, lat + k);
  }
}

TEST(LinkParams, JsonOverridesAndErrorsNameTheKey) {
  auto p = linkParamsFromJson(nlohmann::json::parse(R"({"type":"qpi","read_gbps":3,"max_reads":16})"),
                              "scene.link", LinkParams::qpi());
  EXPECT_EQ(p.readGBps, 3.0);
  EXPECT_EQ(p.maxReads, 16u);
  try {
    linkParamsFromJson(nlohmann::json::parse(R"({"read_latency_ns":[300,200]})"), "scene.link", LinkParams::qpi());
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "scene.link.read_latency_ns: expected 0 <= min <= max, got [300,200]");
  }
}

TEST(LinkModel, ReadyDropsAreRandomButReplayableAndTakeNothingThatIsNotReady) {
  HostMemory mem;
  mem.allocate(4);
  LinkParams p = LinkParams::ideal();
  p.readyDrop = 0.4;
  p.seed = test::testSeed(7);
  auto run = [&] {
    LinkModel link(p, mem);
    std::vector<int> ready;
    for (int c = 0; c < 4000; ++c) {
      const auto o = link.outputs();
      ready.push_back(o.rdReqReady + 2 * o.wrReqReady);
      link.tick(AfuToLink{});
    }
    return ready;
  };
  const auto a = run(), b = run();
  EXPECT_EQ(a, b) << "the same seed must drop the same cycles";
  const double rd = std::count_if(a.begin(), a.end(), [](int r) { return r & 1; }) / 4000.0;
  const double wr = std::count_if(a.begin(), a.end(), [](int r) { return r & 2; }) / 4000.0;
  EXPECT_NEAR(rd, 0.6, 0.05);
  EXPECT_NEAR(wr, 0.6, 0.05);
  p.readyDrop = 0.95;
  EXPECT_THROW(p.validate(), std::invalid_argument);
}
