// The wall-clock watchdog: a stuck AFU stepped cycle by cycle (skipping off) is stopped by
// its wall-clock limit, and each watchdog's message names it. Only which watchdog fired is
// asserted, never how long it took, so a loaded machine cannot make it flaky: the
// simulated-cycle watchdog is set out of reach when the wall clock is under test.
#include <gtest/gtest.h>

#include <limits>

#include "collide/rtl_backend.hpp"
#include "driver/wall_watchdog.hpp"
#include "scene/scene.hpp"
#include "support/model_afu.hpp"
#include "support/random_batch.hpp"

using namespace collide;

namespace {
std::string hangMessage(double wallLimitS, std::uint64_t watchdogCycles) {
  SphereTable t;
  PairList p;
  test::randomBatch(1, 10, 40, t, p);
  test::ModelAfuConfig mc;
  mc.hang = true;
  driver::DriverOptions o;
  o.skipIdle = false;  // every cycle stepped, as with --no-skip
  o.watchdogCycles = watchdogCycles;
  RtlBackend rtl(std::make_unique<test::ModelAfu>(mc), link::LinkParams::qpi(), o, wallLimitS);
  ContactSet out;
  try {
    rtl.collide(t, p, out);
  } catch (const driver::AfuError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(WallWatchdog, AStuckAfuIsStoppedByTheWallClockAndSaysSo) {
  const std::string e = hangMessage(0.05, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(e.rfind("AFU hung: no status line after ", 0), 0u) << e;
  EXPECT_NE(e.find("(wall-clock watchdog, limit 0.05 s"), std::string::npos) << e;
}

TEST(WallWatchdog, TheSimulatedCycleWatchdogSaysSoToo) {
  const std::string e = hangMessage(driver::kMaxWallLimitS, 20'000);
  EXPECT_NE(e.find("after 20000 cycles (simulated-cycle watchdog)"), std::string::npos) << e;
}

TEST(WallWatchdog, LimitsOutsideTheRangeAreRefused) {
  test::ModelAfuConfig mc;
  for (double bad : {0.0, -1.0, 2e6, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(RtlBackend(std::make_unique<test::ModelAfu>(mc), link::LinkParams::qpi(), {}, bad),
                 std::invalid_argument)
        << bad;
  const auto scene = [](const char* limit) {
    return scene::parseScene(nlohmann::json::parse(std::string(R"({"steps": 1, "dt": 0.01, "wall_limit_s": )") + limit +
                                                   R"(, "bodies": {"diamond": {"hMax": 2}}})"));
  };
  EXPECT_EQ(*scene("2.5").wallLimitS, 2.5);
  try {
    scene("1e9");
    FAIL() << "no error";
  } catch (const scene::SceneError& e) {
    EXPECT_STREQ(e.what(), "scene.wall_limit_s: expected a number of seconds in (0, 1e6], got 1000000000.0");
  }
}
