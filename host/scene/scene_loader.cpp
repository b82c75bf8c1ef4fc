#include "scene/scene.hpp"

#include <cmath>
#include <fstream>

#include "link/link_presets.hpp"
#include "scene/diamond.hpp"
#include "scene/random_cloud.hpp"

namespace collide::scene {

namespace {

constexpr long long kMaxSpheres = 1'000'000;  // a guard against typos, not a model limit

void addDiamond(const JsonNode& n, Scene& s) {
  n.allowOnly({"hMax", "dSph", "mass"});
  DiamondParams p;
  const long long h = n.at("hMax").positiveInt();
  if (h > 100) n.at("hMax").expected("an integer in 1..100");
  p.hMax = static_cast<int>(h);
  if (auto d = n.find("dSph")) p.dSph = d->nonNegative();
  const double mass = n.find("mass") ? n.at("mass").positive() : 1.0;
  for (const auto& c : diamondCentres(p)) s.spheres.push_back({c, p.radius, mass, {}});
}

void addSpheres(const JsonNode& n, Scene& s) {
  const std::size_t count = n.arraySize();
  for (std::size_t k = 0; k < count; ++k) {
    const JsonNode e = n[k];
    e.allowOnly({"pos", "r", "mass", "vel"});
    SphereBody b;
    b.pos = e.at("pos").vec3();
    b.radius = e.at("r").positive();
    if (auto m = e.find("mass")) b.mass = m->positive();
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
  p.min = n.at("min").vec3();
  p.max = n.at("max").vec3();
  for (int c = 0; c < 3; ++c)
    if (!(p.max[c] >= p.min[c])) n.at("max").fail("must be >= min in every coordinate");
  const JsonNode r = n.at("radius");
  if (r.json().is_array()) {
    if (r.arraySize() != 2) r.expected("a radius or [rMin, rMax]");
    p.rMin = r[0].positive();
    p.rMax = r[1].positive();
    if (p.rMax < p.rMin) r.fail("rMax < rMin");
  } else {
    p.rMin = p.rMax = r.positive();
  }
  const double mass = n.find("mass") ? n.at("mass").positive() : 1.0;
  for (const auto& c : randomCloud(p)) s.spheres.push_back({c.centre, c.radius, mass, {}});
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
  root.allowOnly({"name", "about", "steps", "dt", "backend", "afu", "link", "world", "effects", "contact", "bodies"});
  Scene s;
  if (auto v = root.find("name")) s.name = v->string();
  if (auto v = root.find("about")) readAbout(*v);
  s.steps = root.at("steps").positiveInt();
  s.dt = root.at("dt").positive();
  if (auto v = root.find("backend")) {
    s.backend = v->string();
    if (s.backend != "ode" && s.backend != "simd" && s.backend != "rtl") v->expected("\"ode\", \"simd\" or \"rtl\"");
  }
  if (auto v = root.find("afu")) {
    s.afuDir = v->string();
    if (s.afuDir.is_relative() && !baseDir.empty()) s.afuDir = baseDir / s.afuDir;
  }

  const JsonNode bodies = root.at("bodies");
  bodies.allowOnly({"diamond", "spheres", "random_cloud"});
  if (auto d = bodies.find("diamond")) addDiamond(*d, s);
  if (auto l = bodies.find("spheres")) addSpheres(*l, s);
  if (auto c = bodies.find("random_cloud")) addCloud(*c, s);
  if (s.spheres.empty()) bodies.fail("no spheres (declare diamond, spheres or random_cloud)");
  if (static_cast<long long>(s.spheres.size()) > kMaxSpheres) bodies.fail("more than 1000000 spheres");

  if (auto v = root.find("effects")) readEffects(*v, s);  // after bodies: "centroid"
  if (auto v = root.find("contact")) readContact(*v, s);
  if (auto v = root.find("world")) readWorld(*v, s);
  if (auto v = root.find("link")) readLink(*v, s);
  return s;
}

Scene loadScene(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw SceneError(file.string() + ": cannot open");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw SceneError(file.string() + ": not valid JSON: " + e.what());
  }
  Scene s = parseScene(j, file.parent_path());
  if (s.name.empty()) s.name = file.stem().string();
  return s;
}

}  // namespace collide::scene
