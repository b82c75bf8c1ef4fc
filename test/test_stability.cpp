// Long-horizon stability per arithmetic, the short version (bench/stability runs 2,000 steps):
// scenes at rest from their first step (scenes/rest_pile.json, scenes/rest_stack.json) under
// gravity, their sphere/sphere contacts computed by each emulated SCPU preset (model:<preset>,
// bit for bit the golden model), stay at rest: no error (a NaN or a sphere flung out of range
// stops a run), no sphere through a wall, no contact deeper than the rest allows, and kinetic
// energy bounded by what the format's resolution can inject. The bounds are physics, stated
// with the scene's numbers; they are not fitted to the measured values (bench/stability has those).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "collide/model_backend.hpp"
#include "scene/scene.hpp"
#include "scpu/scpu_model.hpp"
#include "simulation/simulation.hpp"

using namespace collide;

namespace {
constexpr int kSteps = 300;
constexpr int kSettle = 100;  // steps for a pile to take up its own weight

// The spacing of the link format's values at the scene's largest coordinate: how far apart two
// positions the backend sees can be.
double resolution(const scene::Scene& s, const format::NumberFormat& f) {
  double m = 0;
  for (const auto& b : s.spheres)
    for (double c : b.pos) m = std::max(m, std::fabs(c));
  return std::ldexp(1.0, std::max(std::ilogb(m), f.minExp()) - (f.sigBits - 1));
}

void staysAtRest(const char* file, const std::string& preset) {
  const scene::Scene s = scene::loadScene(std::string(COLLIDE_REPO_SCENES) + "/" + file);
  ModelBackend b(preset);
  sim::Simulation sim(s, b);
  const double q = resolution(s, numberFormat(b.format()));
  const double mass = s.spheres.front().mass, n = static_cast<double>(s.spheres.size());
  // A depth error of q is pushed out at ERP q / dt (20 q per second here); allow every sphere
  // that speed plus 1 cm/s of settling, as kinetic energy.
  const double v = 0.01 + *s.worldErp * q / s.dt;
  const double keBound = n * 0.5 * mass * v * v;
  // Penetration: the 1 mm surface layer, the contact spring's give under the pile (< 1 mm), and
  // a few format steps of position error.
  const double depthBound = 0.003 + 4 * q;
  double maxKe = 0, maxDepth = 0;
  for (int k = 0; k < kSteps; ++k) {
    sim::StepStats st;
    ASSERT_NO_THROW(st = sim.step()) << file << " " << preset << ", step " << k;
    ASSERT_EQ(st.escaped, 0u) << file << " " << preset << ", step " << k << ": a sphere went through a wall";
    ASSERT_GT(st.contacts, 0u) << file << " " << preset << ", step " << k << ": the pile fell apart";
    // Checked every step, so a run that goes wrong stops at once.
    ASSERT_LE(st.maxDepthM, depthBound) << file << " " << preset << ", step " << k << " (resolution " << q << " m)";
    maxDepth = std::max(maxDepth, st.maxDepthM);
    if (k >= kSettle) {
      ASSERT_LE(st.kineticJ, keBound) << file << " " << preset << ", step " << k << " (resolution " << q << " m)";
      maxKe = std::max(maxKe, st.kineticJ);
    }
  }
  std::printf("%s %-12s deepest %.3g mm (bound %.3g), kinetic energy after step %d at most %.3g J (bound %.3g)\n",
              file, preset.c_str(), 1e3 * maxDepth, 1e3 * depthBound, kSettle, maxKe, keBound);
}
}  // namespace

TEST(Stability, ARestingPileStaysAtRestInEveryEmulatedPreset) {
  for (const auto& p : scpu::emulatedPresets()) staysAtRest("rest_pile.json", p.name);
}

TEST(Stability, ARestingStackStaysAtRestInEveryEmulatedPreset) {
  for (const auto& p : scpu::emulatedPresets()) staysAtRest("rest_stack.json", p.name);
}
