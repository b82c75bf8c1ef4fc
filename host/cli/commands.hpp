#pragma once
// The `collide` subcommands. Each returns the process exit code:
// 0 ok, 1 error (message on stderr), 2 what this build cannot do: an AFU it lacks, world mode
// on the AFU (command_errors.hpp maps them).
#include <cstdint>
#include <vector>
#include <optional>
#include <string>

#include "driver/wall_watchdog.hpp"
#include "link/link_presets.hpp"

namespace collide::cli {

struct RunOptions {
  std::string scene;
  std::optional<std::string> backend;  // overrides the scene's
  std::optional<long long> steps;      // overrides the scene's
  std::string out;                     // per-step CSV
  bool perStep = false;
  std::optional<std::string> link;     // rtl: a link preset name, overrides the scene's
  std::string trace;                   // rtl: waveform file (.fst / .vcd)
  bool noSkip = false;                 // rtl: evaluate every cycle (no idle skipping)
  std::string summary;                 // totals as JSON
  int cpuRepeat = 1;                   // time ODE and simd this many times a step, keep the least
  std::string positions;               // final sphere positions as CSV
  std::optional<double> wallLimit;     // rtl: wall-clock seconds an AFU run may take; overrides the scene's
  std::optional<double> clockMHz;      // rtl: the AFU's clock, over the scene's link or --link
};

struct PairsOptions {
  std::string kind = "sphere-sphere";  // or sphere-plane, capsule-sphere (docs/pair-kinds.md)
  std::string afu;      // rtl with the AFU in this generated/<preset> folder
  std::string backend;  // simd | ode (until the AFU exists)
  std::string link = link::kDefaultPreset;  // rtl only: a link preset name
  std::string in, out;  // "-" = stdin/stdout
  bool dense = false;   // rtl: dense mode
  std::string trace;    // rtl: waveform file (.fst / .vcd)
  bool noSkip = false;  // rtl: evaluate every cycle
  double wallLimit = driver::kDefaultWallLimitS;  // rtl: wall-clock seconds an AFU run may take
  std::optional<double> clockMHz;  // rtl: the AFU's clock instead of the preset's
};

struct SpheresOptions {
  // simd (our grid + binary32 kernel) | grid (the tuned grid) | ode (an ODE space + dCollide) |
  // bullet, fcl (that engine's broad phase + the binary32 kernel, where built)
  std::string backend = "simd";
  std::optional<unsigned> threads;  // grid: threads (unset: every hardware thread)
  // ode: hash | sap | quadtree; bullet: dbvt | sap; fcl: tree | sap | hash ("": the default)
  std::string space;
  std::string afu;               // world mode on this generated AFU (manifest afu.world); "" with backend rtl: the built-in one
  std::string link = link::kDefaultPreset;  // rtl: a link preset name
  std::optional<double> clockMHz; // rtl: the AFU's clock instead of the preset's
  std::string in, out;           // "-" = stdin/stdout
  int repeat = 1;                // run the whole collision this many times, report the fastest of each phase
  std::string summary;           // counts and times as JSON
};
// The most `collide spheres --threads` takes.
inline constexpr int kMaxThreads = 1024;
// The faster of ODE's two spaces on bench/world's clouds (bench/results/world).
inline constexpr const char* kDefaultOdeSpace = "sap";
// Bullet's and FCL's defaults: their dynamic AABB trees, what each engine's own worlds use.
inline constexpr const char* kDefaultBulletSpace = "dbvt";
inline constexpr const char* kDefaultFclSpace = "tree";

struct InfoOptions {
  std::string afu;     // print this generated AFU's manifest...
  bool links = false;  // ...or list the link presets
};

int runScene(const RunOptions& o);
int runPairs(const PairsOptions& o);
int runKindPairs(const PairsOptions& o);  // runPairs for the kinds beyond spheres
// "3 pairs: 2 non-finite input (8), 1 outside the host's range (32)": the problem flags among
// `flags` (contract::REC_*), each with its count; empty when none is set.
std::string flaggedSummary(const std::vector<std::uint8_t>& flags);
int runInfo(const InfoOptions& o);
int runSpheres(const SpheresOptions& o);

}  // namespace collide::cli
