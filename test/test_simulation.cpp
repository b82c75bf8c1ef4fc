// ODE integration: only declared effects act; contacts become joints; backends agree.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "scene/scene.hpp"
#include "simulation/simulation.hpp"
#include "world/cpu_world.hpp"

using namespace collide;

namespace {
scene::Scene parse(const std::string& j) { return scene::parseScene(nlohmann::json::parse(j)); }
}  // namespace

TEST(Simulation, UndeclaredEffectsDoNotAct) {
  const auto s = parse(R"({"steps": 10, "dt": 0.01, "bodies": {"spheres": [{"pos": [0, 0, 1], "r": 0.1}]}})");
  OdeBackend b;
  sim::Simulation sim(s, b);
  for (int k = 0; k < 10; ++k) sim.step();
  const dReal* p = dBodyGetPosition(sim.world().sphereBody(0));
  EXPECT_EQ(p[0], 0.0);
  EXPECT_EQ(p[1], 0.0);
  EXPECT_EQ(p[2], 1.0);  // no gravity unless declared
}

TEST(Simulation, DeclaredGravityAndGroundAct) {
  const auto s = parse(R"({"steps": 200, "dt": 0.01, "effects": {"gravity": [0, 0, -9.81], "ground": {"z": 0}},
      "bodies": {"spheres": [{"pos": [0, 0, 0.5], "r": 0.1}]}})");
  SimdBackend b;
  sim::Simulation sim(s, b);
  std::size_t plane = 0;
  for (int k = 0; k < 200; ++k) plane += sim.step().otherContacts;
  const dReal* p = dBodyGetPosition(sim.world().sphereBody(0));
  EXPECT_GT(plane, 0u);                 // sphere/plane went through dCollide on the CPU
  EXPECT_NEAR(p[2], 0.1, 0.02);         // resting on the ground
}

TEST(Simulation, HeadOnSpheresCollideAndSeparate) {
  for (const char* backend : {"ode", "simd"}) {
    const auto s = parse(R"({"steps": 100, "dt": 0.01, "contact": {"bounce": 1.0, "bounce_vel": 0.0},
        "bodies": {"spheres": [{"pos": [-0.5, 0, 0], "r": 0.1, "vel": [1, 0, 0]},
                               {"pos": [0.5, 0, 0], "r": 0.1, "vel": [-1, 0, 0]}]}})");
    std::unique_ptr<CollisionBackend> b;
    if (std::string(backend) == "ode") b = std::make_unique<OdeBackend>();
    else b = std::make_unique<SimdBackend>();
    sim::Simulation sim(s, *b);
    std::size_t contacts = 0;
    for (int k = 0; k < 100; ++k) contacts += sim.step().contacts;
    EXPECT_GT(contacts, 0u) << backend;
    // Elastic bounce: they fly apart again, first sphere now moving in -x.
    const dReal* v = dBodyGetLinearVel(sim.world().sphereBody(0));
    EXPECT_LT(v[0], -0.5) << backend;
  }
}

TEST(Simulation, DiamondBackendsSeeTheSamePairs) {
  const auto s = parse(R"({"steps": 5, "dt": 0.01, "world": {"cfm": 1e-5},
      "effects": {"attractor": {"point": "centroid", "force": 1.0}},
      "contact": {"mu": "infinity", "bounce": 1.0, "bounce_vel": 0.1, "soft_cfm": 0.001},
      "bodies": {"diamond": {"hMax": 4, "dSph": 0}}})");
  OdeBackend o;
  SimdBackend m;
  sim::Simulation a(s, o), b(s, m);
  const auto sa = a.step(), sb = b.step();
  EXPECT_EQ(sa.pairsTested, sb.pairsTested);
  EXPECT_GT(sa.contacts, 0u);
  // Touching in-layer neighbours sit exactly at d = 2r in exact arithmetic, so float and
  // double may classify a few differently; overlapping inter-layer pairs agree.
  EXPECT_NEAR(static_cast<double>(sa.contacts), static_cast<double>(sb.contacts), 0.5 * sa.contacts);
}

TEST(Simulation, OffloadingTheWorldFindsThePairPathsContactsAndPlanes) {
  // The same start through ODE's space + simd pairs and through the world engine (our grid
  // + simd): every contact of the first step, sphere/sphere and sphere/plane, in both.
  const auto s = parse(R"({"steps": 3, "dt": 0.01, "backend": "simd", "collision": {"offload": "world"},
      "effects": {"gravity": [0, 0, -9.81], "planes": [{"normal": [0, 0, 1], "offset": 0}, {"normal": [1, 0, 0], "offset": -1}]},
      "bodies": {"random_cloud": {"count": 400, "seed": 3, "min": [-1, -1, 0.02], "max": [1, 1, 1.2], "radius": [0.04, 0.08]}}})");
  ASSERT_TRUE(s.offload == scene::Scene::Offload::World);
  SimdBackend simd;
  world::CpuWorld engine;
  sim::Simulation pairs(s, simd), whole(s, engine);
  const auto a = pairs.step(), b = whole.step();
  EXPECT_GT(a.contacts, 100u);
  EXPECT_EQ(a.contacts, b.contacts);
  EXPECT_GT(a.otherContacts, 0u);
  EXPECT_EQ(a.otherContacts, b.otherContacts);
  EXPECT_GE(b.pairsTested, b.contacts);  // the engine's candidates
  EXPECT_GT(b.worldBroadNs, 0);
  for (int k = 0; k < 2; ++k) EXPECT_GT(whole.step().contacts, 0u);
}

TEST(Simulation, SweepAndPruneFindsWhatTheHashSpaceFinds) {
  // "collision": {"space": "sap"} swaps ODE's broad phase only: the first step's candidate
  // pairs (as unordered pairs), contacts and plane contacts are those of the hash space.
  auto run = [](const std::string& space) {
    const auto s = parse(R"({"steps": 1, "dt": 0.01, "collision": {"space": ")" + space + R"("},
        "effects": {"gravity": [0, 0, -9.81], "ground": {"z": 0}},
        "bodies": {"random_cloud": {"count": 600, "seed": 11, "min": [-1, -1, 0.02], "max": [1, 1, 1], "radius": [0.03, 0.09]}}})");
    SimdBackend b;
    sim::Simulation sim(s, b);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    sim.setBatchObserver([&](const SphereTable&, const PairList& p, const ContactSet&) {
      for (std::size_t k = 0; k < p.size(); ++k) pairs.emplace_back(std::min(p.i[k], p.j[k]), std::max(p.i[k], p.j[k]));
    });
    const auto st = sim.step();
    std::sort(pairs.begin(), pairs.end());
    return std::make_pair(st, pairs);
  };
  const auto [hash, hashPairs] = run("hash");
  const auto [sap, sapPairs] = run("sap");
  EXPECT_GT(hash.contacts, 50u);
  EXPECT_GT(hash.otherContacts, 0u);
  EXPECT_EQ(hashPairs, sapPairs);
  EXPECT_EQ(hash.contacts, sap.contacts);
  EXPECT_EQ(hash.otherContacts, sap.otherContacts);
  EXPECT_THROW(parse(R"({"steps": 1, "dt": 0.01, "collision": {"space": "octree"}, "bodies": {"spheres": [{"pos": [0, 0, 0], "r": 1}]}})"),
               scene::SceneError);
}

TEST(Simulation, EveryStepSaysWhereItsTimeWent) {
  const auto s = parse(R"({"steps": 30, "dt": 0.01, "effects": {"gravity": [0, 0, -9.81], "ground": {"z": 0}},
      "bodies": {"random_cloud": {"count": 200, "seed": 7, "min": [-1, -1, 0.1], "max": [1, 1, 1], "radius": [0.05, 0.1]}}})");
  SimdBackend b;
  sim::Simulation sim(s, b);
  std::size_t plane = 0, contacts = 0;
  for (int k = 0; k < 30; ++k) {
    const auto st = sim.step();
    plane += st.otherContacts;
    contacts += st.contacts;
    // Every stage was timed, and the stages lie inside the step.
    EXPECT_GT(st.broadNs, 0) << k;
    EXPECT_GT(st.solverNs, 0) << k;
    EXPECT_GE(st.stepNs, st.broadNs + st.otherNarrowNs + st.backendNs + st.jointsNs + st.solverNs) << k;
  }
  EXPECT_GT(plane, 0u) << "the ground's contacts went through the timed sphere/plane stage";
  EXPECT_GT(contacts, 0u);
}
