#pragma once
// The SCPU in C++, bit for bit, for the presets whose every operator is correctly rounded
// (digit-recurrence roots, round to nearest even, subnormals kept) in a format binary64
// emulates exactly (scpu_arith.hpp): the golden model's (ScpuModel's) values, kind and flags,
// checked against its vectors (test/vectors, ScpuModelCpp.*). It lets the host run any scene
// in those formats at CPU speed (`--backend model:fp16`), e.g. for long-horizon stability,
// without a Verilated AFU; the rtl backend covers every configuration.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "format/link_format.hpp"
#include "scpu/scpu_arith.hpp"

namespace collide::scpu {

struct EmulatedPreset {
  std::string name;   // the generator's preset name (ScpuConfig.presets)
  ComputeArith arith;
  LinkFormat link;
};

// A backend (scenes, `collide --backend`) computing with this model is named "model:<preset>".
inline constexpr const char* kModelBackendPrefix = "model:";
// The preset a backend name asks this model for ("model:fp16" -> "fp16"), or nothing when the
// name is not a model backend's.
std::optional<std::string> modelBackendPreset(const std::string& backendName);

// The presets this model reproduces: fp32, fp32-robust, fp24, fp16, fp16-robust, bf16, fp64.
const std::vector<EmulatedPreset>& emulatedPresets();
// By name; throws std::invalid_argument naming the known ones, and for the generator's
// other presets why they are not emulated.
const EmulatedPreset& emulatedPreset(const std::string& name);

struct PairResult {
  bool hit = false;
  unsigned kind = 0;        // contract::KIND_*
  double v[7] = {};         // px, py, pz, nx, ny, nz, depth in the link format; zero unless a hit
  double d = 0, w = 0;      // the derived record's values; zero unless a Contact
  std::uint8_t flags = 0;   // the record's flags byte: HIT, kind, NONFINITE, ARITH
};

// One pair; s1, s2: x, y, z, r of spheres i and j as the link carries them.
PairResult collidePair(const ComputeArith& a, const double s1[4], const double s2[4]);

// The contact path (a Contact, 0 < d <= r1 + r2): from the compute-format spheres, the
// normal's unscaled factors u (the difference, or the Robust method's scaled difference), rs =
// r1 + r2, d and w, the position, normal and depth in the compute format. Shared with the
// derived record's rebuild (driver/contact_rebuild.hpp), which receives d and w from the AFU.
void contactPath(RoundedArith& c, const double p1[4], const double p2[4], const double u[3], double rs, double d,
                 double w, double out[7]);

}  // namespace collide::scpu
