#pragma once
// Backend by name: "ode", "simd", "simd64", "rtl" (rtl needs an AFU folder and a link) or
// "model:<preset>" (the SCPU of an AFU preset on the CPU, collide/model_backend.hpp).
#include <filesystem>
#include <memory>
#include <string>

#include "collide/backend.hpp"
#include "driver/afu_driver.hpp"
#include "driver/afu_factory.hpp"
#include "link/link_presets.hpp"

namespace collide {

struct BackendRequest {
  std::string name;                  // ode | simd | simd64 | rtl | model:<preset>
  std::filesystem::path afuDir;      // rtl only
  link::LinkParams link = link::presetParams(link::kDefaultPreset);  // rtl only
  driver::DriverOptions driver;      // rtl only (format and maxSpheres come from the manifest)
  driver::AfuPortOptions port;       // rtl only: trace file, wall-clock limit (its clock is link's)
};

inline constexpr const char* kBackendNames = "ode, simd, simd64, rtl or model:<preset>";
// Empty if `name` names a backend, else why not.
std::string backendNameError(const std::string& name);

// Throws std::invalid_argument for an unknown name, driver::AfuUnavailable for rtl
// without an AFU.
std::unique_ptr<CollisionBackend> makeBackend(const BackendRequest& request);

}  // namespace collide
