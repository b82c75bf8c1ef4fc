#include "collide/backend_factory.hpp"

#include <stdexcept>

#include "collide/model_backend.hpp"
#include "collide/ode_backend.hpp"
#include "collide/rtl_backend.hpp"
#include "collide/simd_backend.hpp"

namespace collide {

std::string backendNameError(const std::string& name) {
  if (name == "ode" || name == "simd" || name == "simd64" || name == "rtl") return "";
  if (const auto preset = scpu::modelBackendPreset(name)) {
    try {
      scpu::emulatedPreset(*preset);
      return "";
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
  }
  return "unknown backend '" + name + "' (expected " + kBackendNames + ")";
}

std::unique_ptr<CollisionBackend> makeBackend(const BackendRequest& r) {
  if (r.name == "ode") return std::make_unique<OdeBackend>();
  if (r.name == "simd") return std::make_unique<SimdBackend>();
  if (r.name == "simd64") return std::make_unique<SimdBackend>(LinkFormat::Binary64);
  if (r.name == "rtl") {
    // The trace's time axis is the link model's clock, whatever the caller left in port.
    driver::AfuPortOptions port = r.port;
    port.clockMHz = r.link.clockMHz;
    return std::make_unique<RtlBackend>(r.afuDir, r.link, r.driver, port);
  }
  if (const auto preset = scpu::modelBackendPreset(r.name)) return std::make_unique<ModelBackend>(*preset);
  throw std::invalid_argument("unknown backend '" + r.name + "' (expected " + kBackendNames + ")");
}

}  // namespace collide
