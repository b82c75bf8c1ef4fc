// Deep JSON and huge values: a scene or manifest nested 100,000 levels deep is an error
// naming the file and the key path (it overflowed the stack in the error path before),
// and an error quotes at most util::kEchoChars characters of an offending value.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "cli/pairs_csv.hpp"
#include "driver/manifest.hpp"
#include "scene/scene.hpp"
#include "util/echo.hpp"
#include "util/json_input.hpp"

#include "support/error_of.hpp"

using namespace collide;
namespace fs = std::filesystem;

namespace {
constexpr int kDeep = 100000;
std::string nested(const std::string& open, const std::string& inner, const std::string& close, int n = kDeep) {
  std::string s;
  s.reserve((open.size() + close.size()) * n + inner.size());
  for (int k = 0; k < n; ++k) s += open;
  s += inner;
  for (int k = 0; k < n; ++k) s += close;
  return s;
}
fs::path writeTemp(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("collide-json-limits-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}
using test::errorOf;
const std::string kOk = R"("steps": 1, "dt": 0.01, )";
}  // namespace

TEST(JsonLimits, ADeepSceneNamesTheFileAndTheKeyPath) {
  const auto file = writeTemp("deep_scene.json", "{" + kOk + R"("bodies": {"spheres": )" + nested("[", "", "]") + "}}");
  const std::string e = errorOf([&] { scene::loadScene(file); });
  EXPECT_EQ(e.rfind(file.string() + ": scene.bodies.spheres[0][0]", 0), 0u) << e.substr(0, 300);
  EXPECT_NE(e.find("nested deeper than 64 levels"), std::string::npos) << e.substr(0, 300);
  // Under an object key too, and as deep as allowed still loads.
  const auto keys = writeTemp("deep_keys.json", "{" + kOk + R"("bodies": {"diamond": {"hMax": )" +
                                                      nested(R"({"a": )", "1", "}") + "}}}");
  EXPECT_NE(errorOf([&] { scene::loadScene(keys); }).find("scene.bodies.diamond.hMax.a.a.a"), std::string::npos);
  const auto ok = writeTemp("deep_ok.json", "{" + kOk + R"("name": )" + nested("[", "", "]", util::kMaxJsonDepth - 1) +
                                                R"(, "bodies": {"diamond": {"hMax": 2}}})");
  EXPECT_NE(errorOf([&] { scene::loadScene(ok); }).find("scene.name: expected a string"), std::string::npos);
}

// Found by the fuzzer (test/fuzz): a number beyond binary64 escaped as nlohmann's out_of_range,
// whose message names neither the file nor the problem's place.
TEST(JsonLimits, ANumberBeyondBinary64NamesTheFile) {
  const auto file = writeTemp("huge_number.json", "{" + kOk + R"("bodies": {"diamond": {"hMax": 1e400}}})");
  const std::string e = errorOf([&] { scene::loadScene(file); });
  EXPECT_EQ(e.rfind(file.string() + ": a number out of binary64's range", 0), 0u) << e;
  const std::string m = errorOf([&] { driver::parseManifest(R"({"scpus": -321e308})", "m.json"); });
  EXPECT_EQ(m.rfind("m.json: a number out of binary64's range", 0), 0u) << m;
}

TEST(JsonLimits, ADeepManifestNamesTheFile) {
  const auto file = writeTemp("manifest.json", R"({"link": {"format": )" + nested(R"({"x": )", "1", "}") + "}}");
  const std::string e = errorOf([&] { driver::loadManifest(file.parent_path()); });
  EXPECT_EQ(e.rfind(file.string() + ": manifest.link.format.x.x", 0), 0u) << e.substr(0, 300);
  EXPECT_NE(errorOf([] { driver::parseManifest(nested("[", "", "]"), "built-in"); }).find("built-in: manifest[0][0]"),
            std::string::npos);
}

TEST(JsonLimits, AHugeValueIsEchoedClipped) {
  const std::string big(5'000'000, 'x');
  const std::string e = errorOf([&] {
    scene::parseScene(nlohmann::json::parse(R"({"steps": ")" + big + R"(", "dt": 0.01, "bodies": {}})"));
  });
  EXPECT_EQ(e.rfind("scene.steps: expected a positive integer, got \"xxxx", 0), 0u) << e.substr(0, 200);
  EXPECT_LT(e.size(), 200u);
  EXPECT_EQ(e.substr(e.size() - 3), "...");
  // A huge array in a link parameter, and a bad manifest string.
  std::string arr = "[";
  for (int k = 0; k < 1'000'000; ++k) arr += k ? ",1" : "1";
  arr += "]";
  const std::string l = errorOf([&] {
    scene::parseScene(nlohmann::json::parse("{" + kOk + R"("link": {"type": "qpi", "read_gbps": )" + arr +
                                            R"(}, "bodies": {"diamond": {"hMax": 2}}})"));
  });
  EXPECT_NE(l.find("scene.link.read_gbps: expected a number, got [1,1,1"), std::string::npos) << l.substr(0, 200);
  EXPECT_LT(l.size(), 200u);
  const std::string m = errorOf([&] { driver::parseManifest(R"({"link": {"format": ")" + big + R"("}})", "m.json"); });
  EXPECT_EQ(m.rfind("m.json: link.format: expected binary16", 0), 0u) << m.substr(0, 200);
  EXPECT_LT(m.size(), 250u);
}

TEST(JsonLimits, AHugeCsvFieldIsEchoedClipped) {
  // Below the 64 KiB line limit (a longer line is refused before its fields are read).
  std::istringstream in("x1,y1,z1,r1,x2,y2,z2,r2\n" + std::string(60'000, 'z') + ",0,0,1,0,0,0,1\n");
  SphereTable s;
  PairList p;
  std::vector<std::uint8_t> unfit;
  const std::string e = errorOf([&] { cli::readPairsCsv(in, "in.csv", LinkFormat::Binary32, s, p, unfit); });
  EXPECT_EQ(e.rfind("in.csv:2: x1: not a number: 'zzz", 0), 0u) << e.substr(0, 200);
  EXPECT_NE(e.find("... (60000 bytes)'"), std::string::npos) << e.substr(0, 200);
  EXPECT_LT(e.size(), 200u);
}

TEST(JsonLimits, ManifestTypeErrorsNameTheFileAndTheField) {
  EXPECT_EQ(errorOf([] { driver::parseManifest(R"({"link": {"format": 32}})", "m.json"); }),
            "m.json: link.format: expected a string, got 32");
  EXPECT_EQ(errorOf([] { driver::parseManifest(R"({"afu": {"maxSpheres": "many"}})", "m.json"); }),
            "m.json: afu.maxSpheres: expected a number, got \"many\"");
  EXPECT_EQ(errorOf([] { driver::parseManifest("[1, 2]", "m.json"); }), "m.json: expected a JSON object, got [1,2]");
  const auto dir = writeTemp("x", "").parent_path() / "afu_with_dir";
  fs::create_directories(dir / "manifest.json");
  EXPECT_EQ(errorOf([&] { driver::loadManifest(dir); }), (dir / "manifest.json").string() + ": is a directory, expected a file");
}
