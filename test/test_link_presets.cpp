// The link presets: every one valid, names unique, the numbers as documented in
// link_presets.cpp and docs/host.md, and scenes/JSON reaching them.
#include <gtest/gtest.h>

#include <set>

#include <nlohmann/json.hpp>

#include "link/link_presets.hpp"
#include "scene/scene.hpp"

using namespace collide;
using namespace collide::link;

namespace {
std::string jsonError(const char* text) {
  try {
    linkParamsFromJson(nlohmann::json::parse(text), "scene.link", LinkParams::harp2());
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST(LinkPresets, EveryPresetValidatesAndEveryNameIsUnique) {
  std::set<std::string> names;
  for (const auto& p : presets()) {
    SCOPED_TRACE(p.name);
    EXPECT_NO_THROW(p.params.validate());
    EXPECT_EQ(p.params.name, p.name);
    EXPECT_FALSE(p.description.empty());
    EXPECT_FALSE(p.sources.empty());
    // Channel names unique within a preset (validate() checks it too).
    std::set<std::string> channels;
    for (const auto& c : p.params.channels()) EXPECT_TRUE(channels.insert(c.name).second) << c.name;
  }
  for (const auto& n : presetNames()) EXPECT_TRUE(names.insert(n).second) << n << " names two presets";
  EXPECT_EQ(names, (std::set<std::string>{"ideal", "qpi", "harp1", "harp2", "pac", "cxl"}));
}

TEST(LinkPresets, AliasesAndUnknownNames) {
  EXPECT_EQ(presetParams("harp1").name, "qpi");
  EXPECT_EQ(findPreset("harp1"), findPreset("qpi"));
  EXPECT_EQ(findPreset("pcie"), nullptr);
  try {
    presetParams("pcie");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown link preset \"pcie\" (known: ideal, qpi, harp1, harp2, pac, cxl)");
  }
}

TEST(LinkPresets, TheFactoriesAndTheRegistryAgree) {
  // The registry holds copies made by the factories: same numbers (spot-check the fields
  // that differ between presets).
  const std::pair<const char*, LinkParams> pairs[] = {{"ideal", LinkParams::ideal()}, {"qpi", LinkParams::qpi()},
                                                      {"harp2", LinkParams::harp2()}, {"pac", LinkParams::pac()},
                                                      {"cxl", LinkParams::cxl()}};
  for (const auto& [name, p] : pairs) {
    const LinkParams r = presetParams(name);
    EXPECT_EQ(r.name, p.name);
    EXPECT_EQ(r.clockMHz, p.clockMHz) << name;
    EXPECT_EQ(r.channels().size(), p.channels().size()) << name;
    EXPECT_EQ(r.aggregateReadGBps(), p.aggregateReadGBps()) << name;
    EXPECT_EQ(r.csrWriteNs, p.csrWriteNs) << name;
    EXPECT_EQ(r.pollNs, p.pollNs) << name;
  }
}

TEST(LinkPresets, ClocksChannelsAndAggregateBandwidthAsDocumented) {
  const LinkParams ideal = LinkParams::ideal(), qpi = LinkParams::qpi(), harp2 = LinkParams::harp2(),
                   pac = LinkParams::pac(), cxl = LinkParams::cxl();
  EXPECT_EQ(ideal.clockMHz, 200.0);
  EXPECT_EQ(qpi.clockMHz, 200.0);
  for (const auto* p : {&harp2, &pac, &cxl}) EXPECT_EQ(p->clockMHz, 400.0) << p->name;  // CCI-P

  // ideal: unlimited, i.e. only the port's line a cycle.
  EXPECT_EQ(ideal.aggregateReadGBps(), 0.0);
  EXPECT_EQ(ideal.aggregateWriteGBps(), 0.0);
  // HARP v1 unchanged: 7 / 5 GB/s over one QPI channel.
  ASSERT_EQ(qpi.channels().size(), 1u);
  EXPECT_EQ(qpi.aggregateReadGBps(), 7.0);
  EXPECT_EQ(qpi.aggregateWriteGBps(), 5.0);
  EXPECT_EQ(qpi.portGBps(), 12.8);
  // HARP v2: QPI + two PCIe Gen3 x8, just over 20 GB/s together each way.
  const auto h = harp2.channels();
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[0].name, "QPI");
  EXPECT_EQ(h[1].name, "PCIe0");
  EXPECT_EQ(h[2].name, "PCIe1");
  EXPECT_NEAR(harp2.aggregateReadGBps(), 20.46, 1e-9);
  EXPECT_NEAR(harp2.aggregateWriteGBps(), 20.52, 1e-9);
  EXPECT_GT(harp2.aggregateReadGBps(), 20.0);
  EXPECT_LT(harp2.aggregateReadGBps(), harp2.portGBps());  // the link, not the port, binds
  // The characterisation's cache hit: 25 cycles at 400 MHz, about 62 ns.
  EXPECT_EQ(harp2.nsToCycles(h[0].readLatencyMinNs), 25u);
  for (const auto& c : h) {
    EXPECT_LE(c.readLatencyMinNs, c.readLatencyMaxNs);
    // Each PCIe Gen3 x8 link below its 7.87 GB/s theoretical rate.
    if (c.name != "QPI") {
      EXPECT_LT(c.readGBps, 7.87) << c.name;
    }
  }
  EXPECT_LT(h[0].readLatencyMinNs, h[1].readLatencyMinNs);  // the coherent link is the fast one
  // PAC: one Gen3 x8 at the loopback self-test's 6.23 / 6.26 GB/s.
  ASSERT_EQ(pac.channels().size(), 1u);
  EXPECT_EQ(pac.aggregateReadGBps(), 6.23);
  EXPECT_EQ(pac.aggregateWriteGBps(), 6.26);
  // CXL on PCIe 5.0 x16: 64 GB/s a direction, above the 400 MHz port's 25.6.
  ASSERT_EQ(cxl.channels().size(), 1u);
  EXPECT_EQ(cxl.aggregateReadGBps(), 64.0);
  EXPECT_EQ(cxl.aggregateWriteGBps(), 64.0);
  EXPECT_GT(cxl.aggregateReadGBps(), cxl.portGBps());
  // No published per-call overhead for the newer platforms: HARP v1's kept.
  for (const auto* p : {&harp2, &pac, &cxl}) EXPECT_EQ(p->transactionOverheadNs, qpi.transactionOverheadNs) << p->name;
}

TEST(LinkParams, JsonFlatKeysSetChannelZeroAndChannelsReplacesTheList) {
  const auto flat = linkParamsFromJson(nlohmann::json::parse(R"({"type":"harp2","read_gbps":5,"clock_mhz":300})"),
                                       "scene.link", LinkParams::harp2());
  const auto c = flat.channels();
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].readGBps, 5.0);
  EXPECT_EQ(c[1].readGBps, 6.23);  // untouched
  EXPECT_EQ(flat.clockMHz, 300.0);

  const auto listed = linkParamsFromJson(nlohmann::json::parse(R"({"channels": [
      {"name": "a", "read_gbps": 1, "write_gbps": 2, "read_latency_ns": [10, 20], "write_latency_ns": 30},
      {"name": "b", "read_gbps": 3, "write_gbps": 0, "read_latency_ns": 40, "write_latency_ns": [50, 60]}]})"),
                                         "scene.link", LinkParams::harp2());
  const auto l = listed.channels();
  ASSERT_EQ(l.size(), 2u);
  EXPECT_EQ(l[0].name, "a");
  EXPECT_EQ(listed.readLatencyMaxNs, 20.0);  // channel 0 is the flat fields
  EXPECT_EQ(l[1].writeLatencyMaxNs, 60.0);
  EXPECT_EQ(listed.aggregateReadGBps(), 4.0);
  EXPECT_EQ(listed.aggregateWriteGBps(), 0.0);  // b is unlimited
}

TEST(LinkParams, JsonChannelErrorsNameTheKey) {
  EXPECT_EQ(jsonError(R"({"channels": [{"name": "a", "read_gbps": 1, "write_gbps": 1, "read_latency_ns": 1,
                         "write_latency_ns": 1}], "read_gbps": 2})"),
            "scene.link.read_gbps: give it inside \"channels\" when \"channels\" is set");
  EXPECT_EQ(jsonError(R"({"channels": [{"name": "a", "read_gbps": 1, "write_gbps": 1, "read_latency_ns": 1}]})"),
            "scene.link.channels[0].write_latency_ns: missing");
  EXPECT_EQ(jsonError(R"({"channels": []})"), "scene.link.channels: expected a non-empty array of channels, got []");
  EXPECT_EQ(jsonError(R"({"channels": [{"name": "a", "read_gbps": 1, "write_gbps": 1, "read_latency_ns": 1,
                         "write_latency_ns": 1, "lanes": 8}]})"),
            "scene.link.channels[0].lanes: unknown key (known here: name, read_gbps, write_gbps, read_latency_ns, "
            "write_latency_ns)");
  EXPECT_EQ(jsonError(R"({"channels": [
      {"name": "a", "read_gbps": 1, "write_gbps": 1, "read_latency_ns": 1, "write_latency_ns": 1},
      {"name": "a", "read_gbps": 1, "write_gbps": 1, "read_latency_ns": 1, "write_latency_ns": 1}]})"),
            "scene.link.channels[1].name: \"a\" names two channels");
  EXPECT_EQ(jsonError(R"({"channels": [{"name": "a", "read_gbps": -1, "write_gbps": 1, "read_latency_ns": 1,
                         "write_latency_ns": 1}]})"),
            "scene.link.channels[0].read_gbps: expected >= 0 GB/s (0 = unlimited), got -1");
}

TEST(LinkPresets, ScenesNameEveryPreset) {
  const auto scene = [](const std::string& link) {
    return scene::parseScene(nlohmann::json::parse(R"({"steps": 1, "dt": 0.01, "link": )" + link +
                                                   R"(, "bodies": {"diamond": {"hMax": 2}}})"));
  };
  for (const auto& n : presetNames()) EXPECT_EQ(scene("\"" + n + "\"").link.name, presetParams(n).name) << n;
  const auto s = scene(R"({"type": "harp2", "write_gbps": 7})");
  EXPECT_EQ(s.link.name, "harp2");
  EXPECT_EQ(s.link.channels().size(), 3u);
  EXPECT_EQ(s.link.writeGBps, 7.0);
  try {
    scene(R"({"type": "harp3"})");
    FAIL() << "no error";
  } catch (const scene::SceneError& e) {
    EXPECT_STREQ(e.what(),
                 "scene.link.type: expected \"ideal\", \"qpi\", \"harp1\", \"harp2\", \"pac\" or \"cxl\", got \"harp3\"");
  }
}
