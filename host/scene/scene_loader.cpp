#include "scene/scene.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "batch/pair_kinds.hpp"
#include "batch/sane_ranges.hpp"
#include "driver/wall_watchdog.hpp"
#include "link/link_presets.hpp"
#include "scene/diamond.hpp"
#include "scene/random_cloud.hpp"
#include "scene/stacked_pile.hpp"
#include "scpu/scpu_model.hpp"
#include "util/input_file.hpp"
#include "util/json_input.hpp"

namespace collide::scene {

namespace {

constexpr long long kMaxSpheres = 1'000'000;  // a guard against typos, not a model limit

// A centre ODE's broad phase can place, a radius ODE accepts (batch/sane_ranges.hpp).
Vec3 position(const JsonNode& n) {
  const Vec3 v = n.vec3();
  for (double c : v)
    if (!limits::saneCoordinate(c)) n.expected("[x, y, z] within +-1e6 m (docs/host.md, \"What reaches ODE\")");
  return v;
}
double massOf(const JsonNode& n) {
  const double m = n.positive();
  if (!(m >= limits::kMinMassKg && m <= limits::kMaxMassKg)) n.expected("a mass in [1e-9, 1e9] kg");
  return m;
}
double radius(const JsonNode& n) {
  const double r = n.positive();
  if (!limits::saneRadius(r)) n.expected("a radius in (0, 1e6] m");
  return r;
}

void addDiamond(const JsonNode& n, Scene& s) {
  n.allowOnly({"hMax", "dSph", "mass"});
  DiamondParams p;
  const long long h = n.at("hMax").positiveInt();
  if (h > 100) n.at("hMax").expected("an integer in 1..100");
  p.hMax = static_cast<int>(h);
  if (auto d = n.find("dSph")) p.dSph = d->nonNegative();
  const double mass = n.find("mass") ? massOf(n.at("mass")) : 1.0;
  for (const auto& c : diamondCentres(p)) {
    if (!limits::saneCoordinate(c[0]) || !limits::saneCoordinate(c[1]) || !limits::saneCoordinate(c[2]))
      n.at("dSph").expected("a spacing that keeps the diamond within +-1e6 m");
    s.spheres.push_back({c, p.radius, mass, {}});
  }
}

void addSpheres(const JsonNode& n, Scene& s) {
  const std::size_t count = n.arraySize();
  for (std::size_t k = 0; k < count; ++k) {
    const JsonNode e = n[k];
    e.allowOnly({"pos", "r", "mass", "vel"});
    SphereBody b;
    b.pos = position(e.at("pos"));
    b.radius = radius(e.at("r"));
    if (auto m = e.find("mass")) b.mass = massOf(*m);
    if (auto v = e.find("vel")) b.vel = v->vec3();
    s.spheres.push_back(b);
  }
}

void addCloud(const JsonNode& n, Scene& s) {
  n.allowOnly({"count", "seed", "min", "max", "radius", "mass"});
  CloudParams p;
  p.count = n.at("count").positiveInt();
  if (p.count > kMaxSpheres) n.at("count").expected("at most " + std::to_string(kMaxSpheres));
  p.seed = n.at("seed").seed();
  p.min = position(n.at("min"));
  p.max = position(n.at("max"));
  for (int c = 0; c < 3; ++c)
    if (!(p.max[c] >= p.min[c])) n.at("max").fail("must be >= min in every coordinate");
  const JsonNode r = n.at("radius");
  if (r.json().is_array()) {
    if (r.arraySize() != 2) r.expected("a radius or [rMin, rMax]");
    p.rMin = radius(r[0]);
    p.rMax = radius(r[1]);
    if (p.rMax < p.rMin) r.fail("rMax < rMin");
  } else {
    p.rMin = p.rMax = radius(r);
  }
  const double mass = n.find("mass") ? massOf(n.at("mass")) : 1.0;
  for (const auto& c : randomCloud(p)) s.spheres.push_back({c.centre, c.radius, mass, {}});
}

// {"shape": "block" | "pyramid", "base": [nx, ny], "layers": L, "radius": r, "mass": m,
//  "corner": [x, y, z]} (scene/stacked_pile.hpp)
void addStackedPile(const JsonNode& n, Scene& s) {
  n.allowOnly({"shape", "base", "layers", "radius", "mass", "corner"});
  StackedPileParams p;
  if (auto v = n.find("shape")) {
    const std::string sh = v->string();
    if (sh == "block") p.shape = StackedPileParams::Shape::Block;
    else if (sh == "pyramid") p.shape = StackedPileParams::Shape::Pyramid;
    else v->expected("\"block\" or \"pyramid\"");
  }
  const JsonNode base = n.at("base");
  if (!base.json().is_array() || base.arraySize() != 2) base.expected("[nx, ny]");
  const long long nx = base[0].positiveInt(), ny = base[1].positiveInt(), layers = n.at("layers").positiveInt();
  if (nx > kMaxSpheres || ny > kMaxSpheres || layers > kMaxSpheres || nx * ny * layers > kMaxSpheres)
    n.fail("more than " + std::to_string(kMaxSpheres) + " spheres");
  p.nx = static_cast<int>(nx);
  p.ny = static_cast<int>(ny);
  p.layers = static_cast<int>(layers);
  p.radius = radius(n.at("radius"));
  if (auto c = n.find("corner")) p.corner = position(*c);
  const double mass = n.find("mass") ? massOf(n.at("mass")) : 1.0;
  for (const auto& c : stackedPileCentres(p)) {
    if (!limits::saneCoordinate(c[0]) || !limits::saneCoordinate(c[1]) || !limits::saneCoordinate(c[2]))
      n.fail("a sphere's centre lies beyond +-1e6 m");
    s.spheres.push_back({c, p.radius, mass, {}});
  }
}

Vec3 centroid(const Scene& s) {
  Vec3 c{};
  for (const auto& b : s.spheres)
    for (int k = 0; k < 3; ++k) c[k] += b.pos[k];
  for (int k = 0; k < 3; ++k) c[k] /= static_cast<double>(s.spheres.size());
  return c;
}

// [{"normal": [a, b, c], "offset": d}, ...]: static planes a x + b y + c z = d, free space
// on the normal's side (a box is a floor and four walls facing inward).
void readPlanes(const JsonNode& n, Scene& s) {
  const std::size_t count = n.arraySize();
  for (std::size_t k = 0; k < count; ++k) {
    const JsonNode e = n[k];
    e.allowOnly({"normal", "offset"});
    Plane p;
    p.normal = e.at("normal").vec3();
    const double len = std::sqrt(p.normal[0] * p.normal[0] + p.normal[1] * p.normal[1] + p.normal[2] * p.normal[2]);
    if (!(len > 0)) e.at("normal").fail("must not be the zero vector");
    for (int c = 0; c < 3; ++c) p.normal[c] /= len;
    p.offset = e.at("offset").number() / len;  // the same plane, with a unit normal
    s.planes.push_back(p);
  }
}

void readEffects(const JsonNode& n, Scene& s) {
  n.allowOnly({"gravity", "attractor", "ground", "planes"});
  if (auto g = n.find("gravity")) s.gravity = g->vec3();
  if (auto a = n.find("attractor")) {
    a->allowOnly({"point", "force"});
    Attractor at;
    const JsonNode p = a->at("point");
    if (p.json().is_string()) {
      if (p.string() != "centroid") p.expected("[x, y, z] or \"centroid\"");
      at.point = centroid(s);  // for the diamond: its centre
    } else {
      at.point = p.vec3();
    }
    at.force = a->at("force").nonNegative();
    s.attractor = at;
  }
  if (auto g = n.find("ground")) {
    g->allowOnly({"z"});
    s.groundZ = g->at("z").number();
  }
  if (auto ps = n.find("planes")) readPlanes(*ps, s);
}

void readContact(const JsonNode& n, Scene& s) {
  n.allowOnly({"mu", "bounce", "bounce_vel", "soft_cfm", "friction"});
  if (auto v = n.find("mu")) s.contact.mu = v->nonNegativeOrInfinity();
  if (auto v = n.find("bounce")) {
    s.contact.bounce = v->nonNegative();
    if (*s.contact.bounce > 1) v->expected("a number in [0, 1]");
  }
  if (auto v = n.find("bounce_vel")) s.contact.bounceVel = v->nonNegative();
  if (auto v = n.find("soft_cfm")) s.contact.softCfm = v->nonNegative();
  if (auto v = n.find("friction")) {
    const std::string f = v->string();
    if (f != "coulomb" && f != "force_limit") v->expected("\"coulomb\" or \"force_limit\"");
    s.contact.coulomb = f == "coulomb";
  }
  if (s.contact.bounceVel && !s.contact.bounce) n.at("bounce_vel").fail("needs bounce");
}

void readWorld(const JsonNode& n, Scene& s) {
  n.allowOnly({"cfm", "erp", "quickstep_iterations", "contact_max_correcting_vel", "contact_surface_layer"});
  if (auto v = n.find("cfm")) s.worldCfm = v->nonNegative();
  if (auto v = n.find("erp")) {
    s.worldErp = v->nonNegative();
    if (*s.worldErp > 1) v->expected("a number in [0, 1]");
  }
  if (auto v = n.find("quickstep_iterations")) {
    const long long it = v->positiveInt();
    if (it > 100000) v->expected("an integer in 1..100000");
    s.quickStepIterations = static_cast<int>(it);
  }
  if (auto v = n.find("contact_max_correcting_vel")) s.maxCorrectingVel = v->nonNegative();
  if (auto v = n.find("contact_surface_layer")) s.surfaceLayer = v->nonNegative();
}

// "link": NAME or {"type": NAME, ...overrides}; NAME is any link preset or alias.
void readLink(const JsonNode& n, Scene& s) {
  std::string type;
  if (n.json().is_string()) {
    type = n.string();
  } else {
    n.requireObject();
    type = n.at("type").string();
  }
  const link::LinkPreset* preset = link::findPreset(type);
  if (!preset) {
    // "ideal", "qpi", ... or "cxl", from the registry
    const auto names = link::presetNames();
    std::string list;
    for (std::size_t k = 0; k < names.size(); ++k)
      list += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + ("\"" + names[k] + "\"");
    (n.json().is_string() ? n : n.at("type")).expected(list);
  }
  if (!n.json().is_object()) {
    s.link = preset->params;
    return;
  }
  try {
    s.link = link::linkParamsFromJson(n.json(), n.path(), preset->params);
  } catch (const std::invalid_argument& e) {
    throw SceneError(e.what());
  }
}

// "about": prose for the reader, why the parameters are what they are (JSON has no
// comments): a string or an array of strings (one a line). Checked, not kept.
void readAbout(const JsonNode& n) {
  if (!n.json().is_array()) {
    n.string();
    return;
  }
  for (std::size_t k = 0; k < n.arraySize(); ++k) n[k].string();
}

}  // namespace

Scene parseScene(const nlohmann::json& j, const std::filesystem::path& baseDir) {
  const JsonNode root(j, "scene");
  root.allowOnly({"name", "about", "steps", "dt", "backend", "afu", "link", "wall_limit_s", "world", "effects",
                  "contact", "bodies", "collision"});
  Scene s;
  if (auto v = root.find("name")) s.name = v->string();
  if (auto v = root.find("about")) readAbout(*v);
  s.steps = root.at("steps").positiveInt();
  if (s.steps > kMaxSteps) root.at("steps").expected("an integer in 1..1000000000");
  s.dt = root.at("dt").positive();
  if (!(s.dt >= limits::kMinDtS && s.dt <= limits::kMaxDtS)) root.at("dt").expected("a time step in [1e-9, 10] s");
  if (auto v = root.find("backend")) {
    s.backend = v->string();
    if (const auto preset = scpu::modelBackendPreset(s.backend)) {
      try {
        scpu::emulatedPreset(*preset);
      } catch (const std::invalid_argument& e) {
        v->expected(std::string("\"model:<preset>\" with an emulated preset: ") + e.what());
      }
    } else if (s.backend != "ode" && s.backend != "simd" && s.backend != "simd64" && s.backend != "rtl") {
      v->expected("\"ode\", \"simd\", \"simd64\", \"rtl\" or \"model:<preset>\"");
    }
  }
  if (auto v = root.find("afu")) {
    s.afuDir = v->string();
    if (s.afuDir.is_relative() && !baseDir.empty()) s.afuDir = baseDir / s.afuDir;
  }
  if (auto c = root.find("collision")) {
    c->allowOnly({"offload", "space", "require"});
    if (auto v = c->find("require")) {
      for (std::size_t k = 0; k < v->arraySize(); ++k) {
        const JsonNode e = (*v)[k];
        const std::string kind = e.string();
        if (!isPairKind(kind)) e.expected(pairKindList());
        s.requireKinds.push_back(kind);
      }
    }
    if (auto v = c->find("offload")) {
      const std::string o = v->string();
      if (o == "pairs") s.offload = Scene::Offload::Pairs;
      else if (o == "world") s.offload = Scene::Offload::World;
      else v->expected("\"pairs\" or \"world\"");
      if (s.offload == Scene::Offload::World && s.backend == "ode")
        v->expected("\"pairs\" with backend ode (\"world\" needs backend simd or rtl: ODE's own space is the pairs path)");
      if (s.offload == Scene::Offload::World && (s.backend == "simd64" || scpu::modelBackendPreset(s.backend)))
        v->expected("\"pairs\" with backend " + s.backend + " (\"world\" needs backend simd or rtl: the CPU's world "
                    "engine is our grid with the binary32 kernel)");
    }
    if (auto v = c->find("space")) {
      const std::string sp = v->string();
      if (sp == "hash") s.space = limits::OdeSpaceKind::Hash;
      else if (sp == "sap") s.space = limits::OdeSpaceKind::SweepAndPrune;
      else v->expected("\"hash\" (ODE's hash space) or \"sap\" (sweep and prune)");
    }
  }

  const JsonNode bodies = root.at("bodies");
  bodies.allowOnly({"diamond", "spheres", "random_cloud", "stacked_pile"});
  if (auto d = bodies.find("diamond")) addDiamond(*d, s);
  if (auto l = bodies.find("spheres")) addSpheres(*l, s);
  if (auto c = bodies.find("random_cloud")) addCloud(*c, s);
  if (auto p = bodies.find("stacked_pile")) addStackedPile(*p, s);
  if (s.spheres.empty()) bodies.fail("no spheres (declare diamond, spheres or random_cloud)");
  if (static_cast<long long>(s.spheres.size()) > kMaxSpheres) bodies.fail("more than 1000000 spheres");
  const auto n = static_cast<long long>(s.spheres.size());
  if (s.offload == Scene::Offload::Pairs && s.space == limits::OdeSpaceKind::Hash && n > limits::kMaxHashSpaceSpheres)
    bodies.fail(limits::hashSpaceRefusal(n) +
                "; declare \"collision\": {\"space\": \"sap\"} (sweep and prune), or {\"offload\": \"world\"} with "
                "backend simd or rtl");

  if (auto v = root.find("effects")) readEffects(*v, s);  // after bodies: "centroid"
  if (auto v = root.find("contact")) readContact(*v, s);
  if (auto v = root.find("world")) readWorld(*v, s);
  if (auto v = root.find("link")) readLink(*v, s);
  if (auto v = root.find("wall_limit_s")) {
    s.wallLimitS = v->positive();
    if (*s.wallLimitS > driver::kMaxWallLimitS) v->expected("a number of seconds in (0, 1e6]");
  }
  return s;
}

Scene loadScene(const std::filesystem::path& file) {
  nlohmann::json j;
  try {
    std::ifstream in = util::openInput(file);
    j = util::parseJson(in, file.string(), "scene");
  } catch (const util::InputError& e) {
    throw SceneError(e.what());
  } catch (const util::JsonInputError& e) {
    throw SceneError(e.what());
  }
  Scene s = parseScene(j, file.parent_path());
  if (s.name.empty()) s.name = file.stem().string();
  return s;
}

}  // namespace collide::scene
