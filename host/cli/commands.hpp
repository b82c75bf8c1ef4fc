#pragma once
// The `collide` subcommands. Each returns the process exit code:
// 0 ok, 1 error (message on stderr), 2 the rtl backend has no AFU in this build.
#include <optional>
#include <string>

namespace collide::cli {

struct RunOptions {
  std::string scene;
  std::optional<std::string> backend;  // overrides the scene's
  std::optional<long long> steps;      // overrides the scene's
  std::string out;                     // per-step CSV
  bool perStep = false;
};

struct PairsOptions {
  std::string afu;      // rtl with the AFU in this generated/<preset> folder
  std::string backend;  // simd | ode (until the AFU exists)
  std::string link = "ideal";  // rtl only
  std::string in, out;  // "-" = stdin/stdout
  bool dense = false;   // rtl: dense mode
};

struct InfoOptions {
  std::string afu;
};

int runScene(const RunOptions& o);
int runPairs(const PairsOptions& o);
int runInfo(const InfoOptions& o);

}  // namespace collide::cli
