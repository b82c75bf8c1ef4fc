// Scene loading: good scenes load as declared; bad ones name the key path and the fault.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/diamond.hpp"
#include "scene/scene.hpp"

using namespace collide::scene;

namespace {
std::string errorOf(const std::string& json) {
  try {
    parseScene(nlohmann::json::parse(json));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}
std::string fileErrorOf(const std::string& name) {
  try {
    loadScene(std::string(COLLIDE_TEST_SCENES) + "/" + name);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}
const char* kOk = R"("steps": 2, "dt": 0.01)";
}  // namespace

TEST(SceneErrors, BadFilesNameTheKeyPath) {
  EXPECT_EQ(fileErrorOf("bad_hmax.json"), "scene.bodies.diamond.hMax: expected a positive integer, got -3");
  EXPECT_EQ(fileErrorOf("bad_sphere_radius.json"), "scene.bodies.spheres[1].r: expected a positive number, got 0");
  EXPECT_EQ(fileErrorOf("bad_effect_key.json").rfind("scene.effects.gravty: unknown key", 0), 0u)
      << fileErrorOf("bad_effect_key.json");
  EXPECT_EQ(fileErrorOf("bad_link.json"), "scene.link.read_latency_ns: expected 0 <= min <= max, got [290,200]");
  EXPECT_NE(fileErrorOf("bad_syntax.json").find("not valid JSON"), std::string::npos);
  EXPECT_NE(fileErrorOf("does_not_exist.json").find("cannot open"), std::string::npos);
}

TEST(SceneErrors, InlineFaults) {
  EXPECT_EQ(errorOf(R"({"dt": 0.01, "bodies": {"diamond": {"hMax": 2}}})"), "scene.steps: missing");
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "bodies": {}})"),
            "scene.bodies: no spheres (declare diamond, spheres or random_cloud)");
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "bodies": {"diamond": {"hMax": 2.5}}})"),
            "scene.bodies.diamond.hMax: expected a positive integer, got 2.5");
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "backend": "gpu", "bodies": {"diamond": {"hMax": 2}}})"),
            "scene.backend: expected \"ode\", \"simd\", \"simd64\", \"rtl\" or \"model:<preset>\", got \"gpu\"");
  EXPECT_EQ(errorOf(std::string("{") + kOk +
                    R"(, "contact": {"mu": -1}, "bodies": {"diamond": {"hMax": 2}}})"),
            "scene.contact.mu: expected a number >= 0 or \"infinity\", got -1");
  EXPECT_EQ(errorOf(std::string("{") + kOk +
                    R"(, "effects": {"gravity": [0, -9.8]}, "bodies": {"diamond": {"hMax": 2}}})"),
            "scene.effects.gravity: expected [x, y, z], got [0,-9.8]");
  EXPECT_EQ(errorOf(std::string("{") + kOk +
                    R"(, "bodies": {"random_cloud": {"count": 5, "seed": 1, "min": [0,0,0], "max": [1,1,-1], "radius": 0.1}}})"),
            "scene.bodies.random_cloud.max: must be >= min in every coordinate");
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "link": "pcie", "bodies": {"diamond": {"hMax": 2}}})"),
            "scene.link: expected \"ideal\", \"qpi\", \"harp1\", \"harp2\", \"pac\" or \"cxl\", got \"pcie\"");
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "collision": {"offload": "everything"}, "bodies": {"diamond": {"hMax": 2}}})"),
            "scene.collision.offload: expected \"pairs\" or \"world\", got \"everything\"");
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "collision": {"offload": "world"}, "bodies": {"diamond": {"hMax": 2}}})"),
            "scene.collision.offload: expected \"pairs\" with backend ode (\"world\" needs backend simd or rtl: ODE's own "
            "space is the pairs path), got \"world\"");
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "backend": "simd64", "collision": {"offload": "world"}, "bodies": {"diamond": {"hMax": 2}}})")
                .rfind("scene.collision.offload: expected \"pairs\" with backend simd64", 0),
            0u);
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "backend": "model:fp16", "collision": {"offload": "world"}, "bodies": {"diamond": {"hMax": 2}}})")
                .rfind("scene.collision.offload: expected \"pairs\" with backend model:fp16", 0),
            0u);
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "backend": "model:fp32-nr", "bodies": {"diamond": {"hMax": 2}}})")
                .rfind("scene.backend: expected \"model:<preset>\" with an emulated preset: SCPU preset 'fp32-nr' is not "
                       "emulated on the CPU: its roots are Newton-Raphson", 0),
            0u);
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "collision": {"ofload": "world"}, "bodies": {"diamond": {"hMax": 2}}})")
                .rfind("scene.collision.ofload: unknown key", 0),
            0u);
  // collision.require names pair kinds (docs/pair-kinds.md), each checked by its index.
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "collision": {"require": ["sphere-sphere", "box-box"]}, "bodies": {"diamond": {"hMax": 2}}})"),
            "scene.collision.require[1]: expected sphere-sphere, sphere-plane or capsule-sphere, got \"box-box\"");
  EXPECT_EQ(errorOf(std::string("{") + kOk + R"(, "collision": {"require": "sphere-plane"}, "bodies": {"diamond": {"hMax": 2}}})")
                .rfind("scene.collision.require: expected an array", 0),
            0u);
}

TEST(Scenes, ExampleScenesLoadAsDeclared) {
  const auto d = loadScene(std::string(COLLIDE_REPO_SCENES) + "/diamond.json");
  EXPECT_EQ(d.spheres.size(), 670u);
  EXPECT_FALSE(d.gravity);  // the paper's world: no gravity
  ASSERT_TRUE(d.attractor);
  const auto c = diamondCentre({10, 0.0, 0.1});
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(d.attractor->point[k], c[k], 1e-12);
  ASSERT_TRUE(d.worldCfm);
  EXPECT_EQ(*d.worldCfm, 1e-5);
  EXPECT_TRUE(std::isinf(d.contact.mu));
  EXPECT_EQ(d.contact.bounce.value_or(-1), 1.0);
  EXPECT_EQ(d.contact.bounceVel.value_or(-1), 0.1);
  EXPECT_EQ(d.contact.softCfm.value_or(-1), 0.001);
  EXPECT_EQ(d.dt, 0.01);
  EXPECT_FALSE(d.groundZ);

  const auto s = loadScene(std::string(COLLIDE_REPO_SCENES) + "/small.json");
  EXPECT_GT(s.spheres.size(), 0u);
  EXPECT_EQ(s.name, "small");
}

TEST(Scenes, RandomCloudIsSeeded) {
  const char* j = R"({"steps": 1, "dt": 0.01, "bodies": {"random_cloud":
      {"count": 50, "seed": 7, "min": [0,0,0], "max": [1,2,3], "radius": [0.1, 0.2]}}})";
  const auto a = parseScene(nlohmann::json::parse(j)), b = parseScene(nlohmann::json::parse(j));
  ASSERT_EQ(a.spheres.size(), 50u);
  for (std::size_t k = 0; k < 50; ++k) {
    EXPECT_EQ(a.spheres[k].pos, b.spheres[k].pos);
    EXPECT_GE(a.spheres[k].radius, 0.1);
    EXPECT_LE(a.spheres[k].radius, 0.2);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(a.spheres[k].pos[c], 0.0);
      EXPECT_LE(a.spheres[k].pos[c], c + 1.0);
    }
  }
}
