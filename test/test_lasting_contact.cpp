// The lasting-contact scenes (scenes/diamond_settle.json, scenes/pile_box.json): their new
// keys load as declared, bad values name the key, and the scenes keep their spheres in
// contact on every step. Contact counts are correctness properties of the run (same count
// on every machine: the simd kernel is bit-exact), never timings.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "collide/simd_backend.hpp"
#include "scene/scene.hpp"
#include "simulation/simulation.hpp"

using namespace collide;

namespace {
std::string errorOf(const std::string& json) {
  try {
    scene::parseScene(nlohmann::json::parse(json));
  } catch (const scene::SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

// The fewest sphere/sphere contacts of any of the first `steps` steps, on simd.
std::size_t fewestContacts(const char* file, int steps) {
  const scene::Scene s = scene::loadScene(std::string(COLLIDE_REPO_SCENES) + "/" + file);
  SimdBackend b;
  sim::Simulation sim(s, b);
  std::size_t fewest = SIZE_MAX;
  for (int k = 0; k < steps; ++k) fewest = std::min(fewest, sim.step().contacts);
  return fewest;
}
}  // namespace

TEST(LastingContact, PlanesAndContactLimitsLoadAsDeclared) {
  const auto s = scene::parseScene(nlohmann::json::parse(R"({"steps": 1, "dt": 0.01, "about": ["why", "these"],
      "world": {"contact_max_correcting_vel": 0.1, "contact_surface_layer": 0.001},
      "effects": {"planes": [{"normal": [0, 0, 2], "offset": 1}, {"normal": [-1, 0, 0], "offset": -0.5}]},
      "contact": {"mu": 0.1, "friction": "coulomb"},
      "bodies": {"spheres": [{"pos": [0, 0, 1], "r": 0.1}]}})"));
  ASSERT_EQ(s.planes.size(), 2u);
  EXPECT_EQ(s.planes[0].normal[2], 1.0);  // normalized, and the offset with it: z = 0.5
  EXPECT_EQ(s.planes[0].offset, 0.5);
  EXPECT_EQ(s.planes[1].normal[0], -1.0);
  EXPECT_EQ(s.planes[1].offset, -0.5);
  EXPECT_EQ(*s.maxCorrectingVel, 0.1);
  EXPECT_EQ(*s.surfaceLayer, 0.001);
  EXPECT_TRUE(s.contact.coulomb);
  const auto d = scene::parseScene(nlohmann::json::parse(R"({"steps": 1, "dt": 0.01,
      "bodies": {"spheres": [{"pos": [0, 0, 1], "r": 0.1}]}})"));
  EXPECT_FALSE(d.contact.coulomb);  // ODE's default: mu a force limit, as the older scenes had it
  EXPECT_TRUE(d.planes.empty());
  EXPECT_FALSE(d.maxCorrectingVel || d.surfaceLayer);
}

TEST(LastingContact, BadValuesNameTheKey) {
  const std::string ok = R"("steps": 1, "dt": 0.01, "bodies": {"diamond": {"hMax": 2}})";
  EXPECT_EQ(errorOf("{" + ok + R"(, "effects": {"planes": [{"normal": [0, 0, 0], "offset": 0}]}})"),
            "scene.effects.planes[0].normal: must not be the zero vector");
  EXPECT_EQ(errorOf("{" + ok + R"(, "effects": {"planes": [{"normal": [0, 0, 1]}]}})"),
            "scene.effects.planes[0].offset: missing");
  EXPECT_EQ(errorOf("{" + ok + R"(, "world": {"contact_surface_layer": -1}})"),
            "scene.world.contact_surface_layer: expected a number >= 0, got -1");
  EXPECT_EQ(errorOf("{" + ok + R"(, "about": 3})"), "scene.about: expected a string, got 3");
  EXPECT_EQ(errorOf("{" + ok + R"(, "contact": {"friction": "dry"}})"),
            "scene.contact.friction: expected \"coulomb\" or \"force_limit\", got \"dry\"");
}

TEST(LastingContact, PlanesHoldSpheresOnTheCpu) {
  // A sphere rolling into a wall at x = 1 (normal -x) stops there: the plane's contacts are
  // found by dCollide on the CPU, never sent to the backend.
  const auto s = scene::parseScene(nlohmann::json::parse(R"({"steps": 1, "dt": 0.01,
      "effects": {"planes": [{"normal": [-1, 0, 0], "offset": -1}]}, "contact": {"mu": 0},
      "bodies": {"spheres": [{"pos": [0, 0, 0], "r": 0.1, "vel": [1, 0, 0]}]}})"));
  SimdBackend b;
  sim::Simulation sim(s, b);
  std::size_t plane = 0, pairs = 0;
  for (int k = 0; k < 200; ++k) {
    const auto st = sim.step();
    plane += st.otherContacts;
    pairs += st.pairsTested;
  }
  EXPECT_GT(plane, 0u);
  EXPECT_EQ(pairs, 0u);
  EXPECT_LE(dBodyGetPosition(sim.world().sphereBody(0))[0], 0.9 + 1e-3);
}

// Floors below each scene's measured fewest contacts on simd (diamond_settle: 2,280 at step
// 28, then 3,420 from step 80; pile_box: 1,640 at step 17, mid-fall), over runs that include
// that step.
TEST(LastingContact, SettledDiamondKeepsThousandsOfContactsEveryStep) {
  EXPECT_GT(fewestContacts("diamond_settle.json", 80), 2000u);
}

TEST(LastingContact, PileKeepsThousandsOfContactsEveryStep) {
  EXPECT_GT(fewestContacts("pile_box.json", 30), 1500u);
}
