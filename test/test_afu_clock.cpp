// The AFU's clock (driver/afu_clock.hpp): the lower of the target and what the Verilog reaches,
// a study's clock when one is named, and the target, said to be unmeasured, without timing.json.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "driver/afu_clock.hpp"

using namespace collide::driver;

namespace {

const std::string kTiming = R"({
  "commit": "abc1234",
  "verilog": {"Afu_x.sv": "00"},
  "families": {
    "cyclonev": {"slowest_block": "Scpu_x", "cells_ps": 26046, "proxy_mhz": 38.39, "routed_estimate_mhz": 24.93},
    "arriav": {"slowest_block": "Collector_x", "cells_ps": 4000, "proxy_mhz": 250.0, "routed_estimate_mhz": 162.3}
  }
})";

}  // namespace

TEST(AfuClock, ReadsTheSlowestBlockOfAFamilyFromTimingJson) {
  const auto c = parseReachedClock(kTiming, "cyclonev", "t.json");
  EXPECT_EQ(c.block, "Scpu_x");
  EXPECT_DOUBLE_EQ(c.cellsNs, 26.046);
  EXPECT_DOUBLE_EQ(c.proxyMHz, 38.39);
  EXPECT_DOUBLE_EQ(c.routedMHz, 24.93);
  EXPECT_EQ(c.commit, "abc1234");
}

TEST(AfuClock, ABadTimingJsonIsAnErrorNamingTheFileAndTheFamily) {
  try {
    parseReachedClock(kTiming, "stratixv", "t.json");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("t.json: no family stratixv"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseReachedClock("{not json", "cyclonev", "t.json"), std::runtime_error);
  EXPECT_THROW(parseReachedClock(R"({"families": {"cyclonev": {"slowest_block": "x", "cells_ps": 0,
      "proxy_mhz": 0, "routed_estimate_mhz": 0}}})", "cyclonev", "t.json"), std::runtime_error);
}

TEST(AfuClock, TimesUseTheLowerOfTheTargetAndTheReachedClock) {
  const auto slow = parseReachedClock(kTiming, "cyclonev", "t.json");
  const auto fast = parseReachedClock(kTiming, "arriav", "t.json");
  const auto a = chooseClock(200, slow, "", std::nullopt);
  EXPECT_DOUBLE_EQ(a.usedMHz, 38.39);
  EXPECT_FALSE(a.reachesTarget());
  EXPECT_NE(a.describe().find("short of the target 200 MHz"), std::string::npos) << a.describe();
  const auto b = chooseClock(200, fast, "", std::nullopt);
  EXPECT_DOUBLE_EQ(b.usedMHz, 200);
  EXPECT_TRUE(b.reachesTarget());
  EXPECT_EQ(b.toJson()["reached"]["slowest_block"], "Collector_x");
}

TEST(AfuClock, AStudyClockIsUsedAsGivenAndSaidToBeOne) {
  const auto slow = parseReachedClock(kTiming, "cyclonev", "t.json");
  const auto c = chooseClock(200, slow, "", 150.0);
  EXPECT_DOUBLE_EQ(c.usedMHz, 150);
  EXPECT_TRUE(c.study);
  EXPECT_NE(c.describe().find("a study"), std::string::npos) << c.describe();
  EXPECT_TRUE(c.toJson()["study"].get<bool>());
}

TEST(AfuClock, WithoutTimingTheTargetIsUsedAndTheReasonGiven) {
  const auto c = chooseClock(200, std::nullopt, "gen/x has no timing.json", std::nullopt);
  EXPECT_DOUBLE_EQ(c.usedMHz, 200);
  EXPECT_FALSE(c.reachesTarget());
  EXPECT_NE(c.describe().find("not known: gen/x has no timing.json"), std::string::npos) << c.describe();
  EXPECT_TRUE(c.toJson()["reached"].is_null());
}
