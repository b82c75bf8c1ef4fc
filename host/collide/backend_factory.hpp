#pragma once
// Backend by name: "ode", "simd" or "rtl" (rtl needs an AFU folder and a link).
#include <filesystem>
#include <memory>
#include <string>

#include "collide/backend.hpp"
#include "link/link_params.hpp"

namespace collide {

struct BackendRequest {
  std::string name;                  // ode | simd | rtl
  std::filesystem::path afuDir;      // rtl only
  link::LinkParams link = link::LinkParams::qpi();  // rtl only
};

// Throws std::invalid_argument for an unknown name, driver::AfuUnavailable for rtl
// without an AFU.
std::unique_ptr<CollisionBackend> makeBackend(const BackendRequest& request);

}  // namespace collide
