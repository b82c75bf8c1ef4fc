// collide: run scenes, collide pair vectors, inspect a generated AFU or the link presets. See docs/host.md.
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "batch/pair_kinds.hpp"
#include "cli/commands.hpp"
#include "collide/backend_factory.hpp"
#include "link/link_presets.hpp"
#include "scene/scene.hpp"
#include "util/echo.hpp"

namespace {

// A whole number in 1..scene::kMaxSteps, or a message that says so; never clamped.
long long parseSteps(const std::string& text) {
  const std::string want = "--steps: expected an integer in 1.." + std::to_string(collide::scene::kMaxSteps) + ", got ";
  if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos)
    throw CLI::ValidationError(want + "'" + collide::util::clip(text) + "'");
  const long long n = std::stoll(text);  // at most 19 digits: no overflow
  if (n < 1 || n > collide::scene::kMaxSteps) throw CLI::ValidationError(want + text);
  return n;
}

// A thread count in 1..kMaxThreads, or a message that names the option; read as text so
// that 0, a negative number and a word get the same message.
unsigned parseThreads(const std::string& text) {
  const std::string want =
      "--threads: expected a whole number of threads in 1.." + std::to_string(collide::cli::kMaxThreads) + ", got ";
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    throw CLI::ValidationError(want + "'" + collide::util::clip(text) + "'");
  const long n = std::stol(text);  // at most 9 digits: no overflow
  if (n < 1 || n > collide::cli::kMaxThreads) throw CLI::ValidationError(want + text);
  return static_cast<unsigned>(n);
}

// CLI11 reads an unknown subcommand as a stray argument and says "A subcommand is
// required"; name it instead.
bool unknownSubcommand(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  const std::string s = argv[1];
  if (s == "run" || s == "pairs" || s == "spheres" || s == "info") return false;
  std::cerr << "collide: unknown subcommand '" << collide::util::clip(s) << "' (expected run, pairs, spheres or info)\n"
            << "Run with --help for more information.\n";
  return true;
}

// --clock-mhz on an AFU subcommand: set only when given, so that 0 is refused as a clock out of
// range rather than read as "not given" (cli/clock_option.hpp checks it).
void addClockOption(CLI::App* sub, std::optional<double>& mhz, const std::string& what) {
  sub->add_option_function<double>("--clock-mhz", [&mhz](double f) { mhz = f; }, "rtl: the AFU's clock in MHz instead of " + what);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace collide::cli;
  if (unknownSubcommand(argc, argv)) return 1;
  CLI::App app{"collide: ODE host for the sphere-collision accelerator"};
  app.require_subcommand(1);
  // Built from the registry, so a new preset needs no edit here; the error lists them.
  const auto linkNames = collide::link::presetNames();

  RunOptions run;
  auto* r = app.add_subcommand("run", "simulate a JSON scene");
  r->add_option("scene", run.scene, "scene file (JSON)")->required()->check(CLI::ExistingFile);
  r->add_option_function<std::string>("--backend", [&](const std::string& b) { run.backend = b; },
                                      "override the scene's backend")
      ->check(CLI::Validator([](std::string& b) { return collide::backendNameError(b); }, "BACKEND", "backend"));
  // Read as text: CLI11 saturates an integer that overflows, and its range check prints
  // the bound of a double (309 digits).
  r->add_option_function<std::string>("--steps", [&](const std::string& n) { run.steps = parseSteps(n); },
                                      "override the scene's steps (1..1000000000)");
  r->add_option("--out", run.out, "write per-step statistics to this CSV file");
  r->add_flag("--per-step", run.perStep, "print one line per step");
  r->add_option_function<std::string>("--link", [&](const std::string& l) { run.link = l; },
                                      "rtl: link preset, overrides the scene's (collide info --links)")
      ->check(CLI::IsMember(linkNames));
  r->add_option("--trace", run.trace, "rtl: write a waveform of the AFU (.fst or .vcd, as built)");
  r->add_flag("--no-skip", run.noSkip, "rtl: evaluate every cycle instead of jumping idle waits");
  r->add_option("--summary", run.summary, "write the run's totals to this JSON file");
  r->add_option("--cpu-repeat", run.cpuRepeat,
                "time ODE's collider and the simd batch this many times a step and keep the fastest")
      ->check(CLI::Range(1, 1000));
  r->add_option("--positions", run.positions, "write the spheres' final positions to this CSV file");
  // The wall-clock watchdog of an AFU run (the simulated-cycle one stays): seconds.
  const auto wallRange = CLI::Range(1e-3, collide::driver::kMaxWallLimitS);
  r->add_option_function<double>("--wall-limit", [&](double s) { run.wallLimit = s; },
                                 "rtl: wall-clock seconds an AFU run may take (default 600), overrides the scene's")
      ->check(wallRange);
  addClockOption(r, run.clockMHz, "the link's (the scene's or --link's)");

  PairsOptions pairs;
  auto* p = app.add_subcommand("pairs", "vector mode: collide the pairs of a CSV file");
  auto* afu = p->add_option("--afu", pairs.afu, "generated AFU folder (rtl backend)");
  p->add_option("--backend", pairs.backend,
                "CPU backend instead of an AFU (simd: binary32, simd64: the same kernel in binary64, ode: binary64, "
                "model:<preset>: an AFU preset's SCPU on the CPU, bit for bit)")
      ->check(CLI::Validator([](std::string& b) {
        return b == "rtl" ? "backend rtl: give --afu DIR instead" : collide::backendNameError(b);
      }, "BACKEND", "backend"))
      ->excludes(afu);
  p->add_option("--link", pairs.link, "rtl: link preset (collide info --links)")
      ->capture_default_str()
      ->check(CLI::IsMember(linkNames));
  p->add_flag("--dense", pairs.dense, "rtl: dense mode (a record per pair)");
  p->add_option("--trace", pairs.trace, "rtl: write a waveform of the AFU (.fst or .vcd, as built)");
  p->add_flag("--no-skip", pairs.noSkip, "rtl: evaluate every cycle instead of jumping idle waits");
  p->add_option("--wall-limit", pairs.wallLimit, "rtl: wall-clock seconds an AFU run may take")
      ->capture_default_str()
      ->check(wallRange);
  addClockOption(p, pairs.clockMHz, "the link preset's");
  p->add_option("--kind", pairs.kind,
                "pair kind: sphere-sphere, sphere-plane (input cx,cy,cz,r,nx,ny,nz,d) or capsule-sphere (input "
                "cx,cy,cz,ax,ay,az,lz,rc,sx,sy,sz,rs); the last two on the simd, simd64 and ode backends (docs/pair-kinds.md)")
      ->capture_default_str()
      ->check(CLI::IsMember(std::vector<std::string>(collide::kPairKinds.begin(), collide::kPairKinds.end())));
  p->add_option("--in", pairs.in, "input CSV (x1,y1,z1,r1,x2,y2,z2,r2, or the --kind's columns), - for stdin")
      ->required();
  p->add_option("--out", pairs.out, "output CSV, - for stdout")->required();

  SpheresOptions spheres;
  auto* w = app.add_subcommand("spheres", "world mode: every contact among the spheres of a CSV file");
  w->add_option("--backend", spheres.backend,
                "simd: our grid + the binary32 kernel; grid: the tuned grid, the same contacts on --threads threads; "
                "ode: an ODE space + dCollide (binary64); bullet, fcl: that engine's broad phase + the binary32 "
                "kernel (where built); rtl: the built-in AFU's world mode")
      ->capture_default_str()
      ->check(CLI::IsMember({"simd", "grid", "ode", "bullet", "fcl", "rtl"}));
  w->add_option_function<std::string>("--threads", [&](const std::string& n) { spheres.threads = parseThreads(n); },
                                      "grid: threads to run on (default: every hardware thread)");
  w->add_option("--space", spheres.space,
                std::string("the engine's broad phase: ode hash, sap or quadtree (default ") + kDefaultOdeSpace +
                    "); bullet dbvt or sap (default " + kDefaultBulletSpace + "); fcl tree, sap or hash (default " +
                    kDefaultFclSpace + ")")
      ->check(CLI::IsMember({"hash", "sap", "quadtree", "dbvt", "tree"}));
  w->add_option("--afu", spheres.afu, "world mode on a generated AFU (the world preset): its broad phase and SCPUs");
  w->add_option("--link", spheres.link, "rtl: link preset (collide info --links)")->capture_default_str()
      ->check(CLI::IsMember(linkNames));
  addClockOption(w, spheres.clockMHz, "the link preset's");
  w->add_option("--in", spheres.in, "input CSV (x,y,z,r), - for stdin")->required();
  w->add_option("--out", spheres.out, "output CSV (i,j,px,py,pz,nx,ny,nz,depth,flags), - for stdout")->required();
  w->add_option("--repeat", spheres.repeat, "collide this many times, report the fastest broad and narrow phase")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  w->add_option("--summary", spheres.summary, "write counts and times to this JSON file");

  InfoOptions info;
  auto* i = app.add_subcommand("info", "print a generated AFU's manifest, or the link presets");
  i->add_option("--afu", info.afu, "generated AFU folder: print its manifest");
  i->add_flag("--links", info.links, "list the link presets: clock, channels, per-call costs, sources");

  CLI11_PARSE(app, argc, argv);
  if (r->parsed()) return runScene(run);
  if (w->parsed()) return runSpheres(spheres);
  if (p->parsed()) {
    if (pairs.afu.empty() && pairs.backend.empty()) {
      std::cerr << "collide pairs: give --afu DIR (rtl) or --backend simd|ode\n";
      return 1;
    }
    return runPairs(pairs);
  }
  // Exactly one of the two: checked here for one clear message either way.
  if ((i->count("--afu") > 0) == info.links) {
    std::cerr << "collide info: give exactly one of --afu DIR (a generated AFU's manifest) or --links (the link presets)\n";
    return 1;
  }
  return runInfo(info);
}
