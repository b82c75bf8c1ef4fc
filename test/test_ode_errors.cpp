// Nothing aborts inside ODE: values are checked before they reach it, ODE's own errors
// become exceptions (ode_errors.hpp), and a body flung out of the sane range mid-run is a
// reported event. Each case here aborted the process (SIGABRT) before.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <tuple>

#include "batch/sane_ranges.hpp"
#include "collide/ode_backend.hpp"
#include "ode/ode_errors.hpp"
#include "ode/ode_world.hpp"
#include "scene/scene.hpp"
#include "simulation/simulation.hpp"

#include "support/error_of.hpp"
#include "util/system_memory.hpp"

using namespace collide;

namespace {
using test::errorOf;
// Vector mode: one pair (0, 0, 0, r1) against (x2, 0, 0, 1); whether ODE was reached is seen
// by the absence of an error (or an abort) and by the result.
std::string vectorError(double r1, double x2, int* hit = nullptr) {
  SphereTable s;
  PairList p;
  s.push(0, 0, 0, r1);
  s.push(x2, 0, 0, 1);
  p.push(0, 1);
  OdeBackend ode;
  ContactSet out;
  const std::string e = errorOf([&] { ode.collide(s, p, out); });
  if (hit) *hit = out.size() ? out.hit[0] : -1;
  return e;
}
scene::Scene parse(const std::string& j) { return scene::parseScene(nlohmann::json::parse(j)); }
}  // namespace

TEST(OdeErrors, BadRadiiNeverReachOdeInVectorMode) {
  // A negative or NaN radius aborted inside ODE once (dGeomSphereSetRadius); now it is no
  // contact (input_policy.hpp flags it).
  for (double r1 : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    int hit = -2;
    EXPECT_EQ(vectorError(r1, 0.0, &hit), "(no error)") << "r1 " << r1;
    EXPECT_EQ(hit, 0) << "r1 " << r1;
  }
  // What ODE takes outside a scene's range is computed: a zero radius at the other's centre
  // is a contact, 1e9 m away is not, and an ordinary pair is.
  for (auto [r1, x2, want] : {std::tuple{0.0, 0.0, 1}, {1.0, 1e9, 0}, {1.0, 0.5, 1}}) {
    int hit = -2;
    EXPECT_EQ(vectorError(r1, x2, &hit), "(no error)") << "r1 " << r1 << " x2 " << x2;
    EXPECT_EQ(hit, want) << "r1 " << r1 << " x2 " << x2;
  }
}

TEST(OdeErrors, MoreSpheresThanOdesHashSpaceHoldsAreRefusedBeforeOde) {
  // A cloud of 140,000 spheres ended in ODE's assertion in dSpaceCollide: its hash space's
  // tested-pairs matrix (n x ceil(n/8) bytes) passes the int range from 131,072 spheres on.
  auto cloud = [](long long n, const std::string& collision) {
    return R"({"steps": 1, "dt": 0.01, "backend": "simd", )" + collision + R"("bodies": {"random_cloud": {"count": )" +
           std::to_string(n) + R"(, "seed": 1, "min": [0, 0, 0], "max": [100, 100, 100], "radius": 0.1}}})";
  };
  const std::string e = errorOf([&] { parse(cloud(limits::kMaxHashSpaceSpheres + 1, "")); });
  EXPECT_EQ(e.rfind("scene.bodies: 131072 spheres, more than ODE's hash space holds (131071", 0), 0u) << e;
  EXPECT_NE(e.find(R"("space": "sap")"), std::string::npos) << e;
  // The largest world the hash space holds, sweep and prune, and world mode are accepted.
  EXPECT_EQ(errorOf([&] { parse(cloud(limits::kMaxHashSpaceSpheres, "")); }), "(no error)");
  EXPECT_EQ(errorOf([&] { parse(cloud(limits::kMaxHashSpaceSpheres + 1, R"("collision": {"space": "sap"}, )")); }),
            "(no error)");
  EXPECT_EQ(errorOf([&] { parse(cloud(limits::kMaxHashSpaceSpheres + 1, R"("collision": {"offload": "world"}, )")); }),
            "(no error)");
}

TEST(OdeErrors, ASceneSphereFarAwayNamesTheKeyPath) {
  const std::string e = errorOf([] {
    parse(R"({"steps": 1, "dt": 0.01, "bodies": {"spheres": [{"pos": [0, 0, 0], "r": 0.1}, {"pos": [1e9, 0, 0], "r": 0.1}]}})");
  });
  EXPECT_EQ(e.rfind("scene.bodies.spheres[1].pos: expected [x, y, z] within +-1e6 m", 0), 0u) << e;
  EXPECT_NE(errorOf([] {
              parse(R"({"steps": 1, "dt": 0.01, "bodies": {"random_cloud": {"count": 2, "seed": 1, "min": [0, 0, 0],
                        "max": [1, 1, 1], "radius": 1e7}}})");
            }).find("scene.bodies.random_cloud.radius: expected a radius in (0, 1e6] m"),
            std::string::npos);
}

TEST(OdeErrors, MassesStepsAndSpacingsOdeCannotTakeAreRefused) {
  // A mass of 1e300 kg or a step of 1e-300 s ended in ODE's quaternion assertion.
  const auto err = [](const std::string& dt, const std::string& bodies) {
    return errorOf([&] { parse(R"({"steps": 1, "dt": )" + dt + R"(, "bodies": )" + bodies + "}"); });
  };
  EXPECT_EQ(err("0.01", R"({"spheres": [{"pos": [0, 0, 0], "r": 0.5, "mass": 1e300}]})"),
            "scene.bodies.spheres[0].mass: expected a mass in [1e-9, 1e9] kg, got 1e+300");
  EXPECT_EQ(err("1e-300", R"({"diamond": {"hMax": 2}})"), "scene.dt: expected a time step in [1e-9, 10] s, got 1e-300");
  EXPECT_EQ(err("0.01", R"({"diamond": {"hMax": 2, "dSph": 1e9}})"),
            "scene.bodies.diamond.dSph: expected a spacing that keeps the diamond within +-1e6 m, got 1000000000.0");
}

TEST(OdeErrors, ABodyFlungAwayMidRunIsAReportedEvent) {
  const auto sc = parse(R"({"steps": 50, "dt": 0.01, "bodies": {"spheres": [
      {"pos": [0, 0, 0], "r": 0.5, "vel": [1e12, 0, 0]}, {"pos": [3, 0, 0], "r": 0.5}]}})");
  OdeBackend ode;
  sim::Simulation sim(sc, ode);
  const std::string e = errorOf([&] {
    for (int s = 0; s < 50; ++s) sim.step();
  });
  EXPECT_EQ(e.rfind("step 1: sphere 0 left the sane range |x|, |y|, |z| <= 1e+06 m, at (1e+10, 0, 0)", 0), 0u) << e;
}

TEST(OdeErrors, WhatOdeStillRejectsIsAnExceptionNotAnAbort) {
  ode::Library lib;
  dGeomID g = dCreateSphere(nullptr, 1);
  const std::string e = errorOf([&] { dGeomSphereSetRadius(g, -1); });
  EXPECT_EQ(e.rfind("ODE assertion 2: Bad argument(s) in dGeomSphereSetRadius()", 0), 0u) << e;
  dGeomDestroy(g);
  // Inside the broad phase too: the world is then destroyed with its space locked, which
  // ODE refuses, so ~World leaves that space alone instead of a second (fatal) error.
  const auto sc = parse(R"({"steps": 1, "dt": 0.01, "bodies": {"spheres": [{"pos": [0, 0, 0], "r": 0.5},
                            {"pos": [0.5, 0, 0], "r": 0.5}]}})");
  const std::string inside = errorOf([&] {
    ode::World w(sc);
    w.collideSpace(nullptr, [](void*, dGeomID o1, dGeomID) { dGeomSphereSetRadius(o1, -1); });
  });
  EXPECT_EQ(inside.rfind("ODE assertion 2: Bad argument(s)", 0), 0u) << inside;
}

TEST(OdeErrors, ASceneLargerThanTheMachinesMemoryIsRefusedBeforeOde) {
  using limits::OdeSpaceKind;
  const unsigned long long gib = 1ULL << 30;
  // A million spheres in sweep and prune: at least about 2.9 GiB; fits 24 GiB, not 1 GiB.
  EXPECT_EQ(limits::memoryRefusal(1'000'000, OdeSpaceKind::SweepAndPrune, 24 * gib), "");
  const auto why = limits::memoryRefusal(1'000'000, OdeSpaceKind::SweepAndPrune, gib);
  EXPECT_NE(why.find("1000000 spheres need at least about 2993 MiB (3072 bytes a sphere)"), std::string::npos) << why;
  EXPECT_NE(why.find("more than the 1024 MiB this machine has available"), std::string::npos) << why;
  // The hash space's tested-pairs matrix is quadratic: 100,000 spheres need 1.2 GiB more.
  EXPECT_EQ(limits::memoryRefusal(100'000, OdeSpaceKind::SweepAndPrune, gib), "");
  const auto hash = limits::memoryRefusal(100'000, OdeSpaceKind::Hash, gib);
  EXPECT_NE(hash.find("and 1192 MiB for the hash space's tested-pairs matrix"), std::string::npos) << hash;
  // This machine's own number is read (Linux).
  EXPECT_TRUE(util::availableMemoryBytes().has_value());
}
