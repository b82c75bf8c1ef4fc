// Every link number is checked against its sane range before anything becomes cycles:
// absurd latencies, bandwidths, clocks and costs overflowed a double-to-integer conversion
// before and came out as a successful, wrong modelled time below its own bound.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "collide/rtl_backend.hpp"
#include "link/link_params.hpp"

using namespace collide;
using namespace collide::link;

namespace {
std::string jsonError(const std::string& text) {
  try {
    linkParamsFromJson(nlohmann::json::parse(text), "scene.link", LinkParams::qpi());
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST(LinkRanges, AbsurdValuesNameTheKeyTheValueAndTheRange) {
  EXPECT_EQ(jsonError(R"({"clock_mhz": 1e12})"),
            "scene.link.clock_mhz: 1e+12 MHz is outside the sane range 1..2000 MHz");
  EXPECT_EQ(jsonError(R"({"clock_mhz": 1e-9})"),
            "scene.link.clock_mhz: 1e-09 MHz is outside the sane range 1..2000 MHz");
  EXPECT_EQ(jsonError(R"({"read_latency_ns": 1e30})"),
            "scene.link.read_latency_ns: 1e+30 ns is outside the sane range 0..1e+06 ns");
  EXPECT_EQ(jsonError(R"({"write_latency_ns": [0, 1e30]})"),
            "scene.link.write_latency_ns: max 1e+30 ns is outside the sane range 0..1e+06 ns");
  EXPECT_EQ(jsonError(R"({"read_gbps": 1e-300})"),
            "scene.link.read_gbps: 1e-300 GB/s is outside the sane range 0 (unlimited) or 0.001..10000 GB/s");
  EXPECT_EQ(jsonError(R"({"write_gbps": 1e300})"),
            "scene.link.write_gbps: 1e+300 GB/s is outside the sane range 0 (unlimited) or 0.001..10000 GB/s");
  EXPECT_EQ(jsonError(R"({"csr_write_ns": 1e30})"),
            "scene.link.csr_write_ns: 1e+30 ns is outside the sane range 0..1e+06 ns");
  EXPECT_EQ(jsonError(R"({"poll_ns": 1e30})"), "scene.link.poll_ns: 1e+30 ns is outside the sane range 0..1e+06 ns");
  EXPECT_EQ(jsonError(R"({"transaction_overhead_ns": 1e300})"),
            "scene.link.transaction_overhead_ns: 1e+300 ns is outside the sane range 0..1e+09 ns");
  EXPECT_EQ(jsonError(R"({"max_reads": 1000000000})"),
            "scene.link.max_reads: expected an integer in 1..1048576, got 1000000000");
  EXPECT_EQ(jsonError(R"({"channels": [
      {"name": "a", "read_gbps": 1, "write_gbps": 1, "read_latency_ns": 1, "write_latency_ns": 1},
      {"name": "b", "read_gbps": 1, "write_gbps": 1, "read_latency_ns": [1, 1e20], "write_latency_ns": 1}]})"),
            "scene.link.channels[1].read_latency_ns: max 1e+20 ns is outside the sane range 0..1e+06 ns");
  // The edges of the ranges are accepted.
  EXPECT_EQ(jsonError(R"({"clock_mhz": 2000, "read_latency_ns": [0, 1e6], "read_gbps": 0.001, "write_gbps": 0,
                          "transaction_overhead_ns": 1e9})"),
            "no error");
}

TEST(LinkRanges, ValidateRefusesWhatNoJsonCanSpell) {
  LinkParams p = LinkParams::qpi();
  p.clockMHz = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = LinkParams::qpi();
  p.pollNs = std::numeric_limits<double>::infinity();
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = LinkParams::qpi();
  p.readLatencyMaxNs = 1e300;
  EXPECT_THROW(p.validate(), std::invalid_argument);  // LinkModel's constructor validates
}

TEST(LinkRanges, AModelledTimeBelowItsBoundIsAnInternalError) {
  driver::RunStats r;
  r.linkBoundNs = 1000;
  r.modelledNs = 1000;
  EXPECT_NO_THROW(requireAtLeastLinkBound(r, "qpi"));
  r.modelledNs = 999;
  try {
    requireAtLeastLinkBound(r, "qpi");
    FAIL() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("internal error: modelled run time 999 ns is below its link bound 1000 ns (link qpi", 0), 0u)
        << e.what();
  }
}
