#pragma once
// `model:<preset>` backend: the SCPU of an AFU preset computed on the CPU, bit for bit
// (scpu/scpu_model.hpp), for the presets whose operators binary64 reproduces exactly (fp32,
// fp32-robust, fp24, fp16, fp16-robust, bf16, fp64). The spheres go into the preset's link
// format as the driver sends them (one RNE rounding; a value that does not fit is flagged
// REC_HOST_RANGE), and every record carries the flags the AFU would write. No link, no
// cycles: it answers "what does this arithmetic do to the physics" at CPU speed.
#include <string>
#include <vector>

#include "collide/backend.hpp"
#include "scpu/scpu_model.hpp"

namespace collide {

class ModelBackend final : public CollisionBackend {
 public:
  // preset: an emulated preset's name; throws std::invalid_argument otherwise.
  explicit ModelBackend(const std::string& preset);
  std::string name() const override { return scpu::kModelBackendPrefix + preset_.name; }
  LinkFormat format() const override { return preset_.link; }
  void collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) override;
  bool setsRecordFlags() const override { return true; }

 private:
  scpu::EmulatedPreset preset_;
  std::vector<double> linkTable_;         // x, y, z, r per sphere in the link format
  std::vector<std::uint8_t> outOfRange_;  // per sphere: a value did not fit the link format
};

}  // namespace collide
