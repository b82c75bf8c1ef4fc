#pragma once
// A scene: bodies, declared effects, contact model, stepping, backend and link.
// Anything optional that is absent is not simulated (no gravity unless declared, ...).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "batch/sane_ranges.hpp"
#include "link/link_params.hpp"
#include "link/link_presets.hpp"
#include "scene/json_reader.hpp"

namespace collide::scene {

// The most steps a run may take (a scene's "steps", `collide run --steps`): a guard
// against typos (10^9 steps of even the smallest scene take days), not a model limit.
inline constexpr long long kMaxSteps = 1'000'000'000;

struct SphereBody {
  Vec3 pos{};
  double radius = 0.1;
  double mass = 1.0;
  Vec3 vel{};
};

struct Attractor {        // a constant-magnitude force on every sphere toward `point`
  Vec3 point{};
  double force = 0.0;     // newtons
};

struct Plane {            // the half-space normal . p >= offset is free space (ODE's dCreatePlane)
  Vec3 normal{0, 0, 1};   // unit length (normalized by the loader)
  double offset = 0.0;
};

struct ContactModel {     // ODE dSurfaceParameters; unset fields leave their mode bit off
  double mu = 0.0;        // 0 = frictionless; infinity allowed
  std::optional<double> bounce, bounceVel;
  std::optional<double> softCfm;
  bool coulomb = false;   // friction force <= mu x normal force (ODE's dContactApprox1, the friction
                          // pyramid); otherwise ODE's default: mu is a fixed force limit in newtons
};

struct Scene {
  std::string name;
  std::vector<SphereBody> spheres;
  // Effects
  std::optional<Vec3> gravity;
  std::optional<Attractor> attractor;
  std::optional<double> groundZ;       // plane z = groundZ, normal +z
  std::vector<Plane> planes;           // more static planes (a box's floor and walls)
  ContactModel contact;
  // World
  std::optional<double> worldCfm, worldErp;
  std::optional<int> quickStepIterations;
  std::optional<double> maxCorrectingVel;   // m/s: caps how fast ERP pushes overlaps apart
  std::optional<double> surfaceLayer;       // m: depth allowed to rest without correction
  // Stepping
  long long steps = 1;
  double dt = 0.01;
  // Collision
  std::string backend = "ode";         // ode | simd | rtl
  // What the backend is given: the broad phase's candidate pairs (ODE's space finds them), or
  // the whole sphere/sphere collision of the world (its own broad phase: our CPU grid with
  // simd, the AFU's world mode with rtl). Planes stay with ODE either way.
  enum class Offload { Pairs, World };
  Offload offload = Offload::Pairs;
  // ODE's broad phase on the pairs path: its hash space (ODE's default, up to
  // limits::kMaxHashSpaceSpheres spheres) or sweep and prune (any count).
  limits::OdeSpaceKind space = limits::OdeSpaceKind::Hash;
  // collision.require: the pair kinds (batch/pair_kinds.hpp) the scene needs the AFU to compute;
  // with backend rtl, a kind the AFU has no units for is refused before any step.
  std::vector<std::string> requireKinds;
  std::filesystem::path afuDir;        // rtl: generated/<preset>
  link::LinkParams link = link::presetParams(link::kDefaultPreset);
  // rtl: wall-clock limit of one AFU run (unset: driver::kDefaultWallLimitS).
  std::optional<double> wallLimitS;
};

// Throws SceneError ("scene.<key path>: <what is wrong>").
Scene loadScene(const std::filesystem::path& file);
Scene parseScene(const nlohmann::json& j, const std::filesystem::path& baseDir = {});

}  // namespace collide::scene
