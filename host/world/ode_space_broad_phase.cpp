#include "world/ode_space_broad_phase.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "batch/sane_ranges.hpp"
#include "ode/hash_space_repair.hpp"
#include "ode/ode_world.hpp"

namespace collide::world {

OdeSpaceBroadPhase::OdeSpaceBroadPhase(OdeSpaceKind kind)
    : kind_(kind),
      space_(ode::createSpace(kind)) {
  dSpaceSetCleanup(space_, 0);  // the geoms are ours (clearGeoms)
}

OdeSpaceBroadPhase::~OdeSpaceBroadPhase() {
  clearGeoms();
  dSpaceDestroy(space_);
}

void OdeSpaceBroadPhase::clearGeoms() {
  for (dGeomID g : geoms_)
    if (g) dGeomDestroy(g);  // also removes it from the space
  geoms_.clear();
}

void OdeSpaceBroadPhase::prepare(const SphereTable& s, const std::vector<std::uint32_t>& members) {
  const auto n = static_cast<long long>(members.size());
  if (kind_ == OdeSpaceKind::Hash && n > limits::kMaxHashSpaceSpheres)
    throw std::invalid_argument(limits::hashSpaceRefusal(n) + ": use --space sap");
  const bool fresh = geoms_.size() != s.size() ||
                     std::any_of(members.begin(), members.end(), [&](std::uint32_t m) { return !geoms_[m]; });
  if (fresh) {
    clearGeoms();
    geoms_.assign(s.size(), nullptr);
    for (auto m : members) {
      geoms_[m] = dCreateSphere(space_, s.r[m]);
      // The sphere index travels with the geom, for the near callback (+1: null is no sphere).
      dGeomSetData(geoms_[m], reinterpret_cast<void*>(static_cast<std::uintptr_t>(m) + 1));
    }
  }
  for (auto m : members) {
    dGeomSphereSetRadius(geoms_[m], s.r[m]);
    dGeomSetPosition(geoms_[m], s.x[m], s.y[m], s.z[m]);
  }
}

void OdeSpaceBroadPhase::nearCallback(void* self, dGeomID o1, dGeomID o2) {
  auto* me = static_cast<OdeSpaceBroadPhase*>(self);
  const auto a = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(dGeomGetData(o1)) - 1);
  const auto b = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(dGeomGetData(o2)) - 1);
  if (me->error_) return;
  try {
    me->out_->push(std::min(a, b), std::max(a, b));
  } catch (...) {
    me->error_ = std::current_exception();
  }
}

void OdeSpaceBroadPhase::findPairs(const SphereTable& s, const std::vector<std::uint32_t>& members, PairList& out) {
  if (geoms_.size() != s.size())
    throw std::logic_error("OdeSpaceBroadPhase::findPairs before prepare on this table");
  (void)members;  // the space holds exactly the members prepare() was given
  out_ = &out;
  ode::collideSpace(space_, this, &OdeSpaceBroadPhase::nearCallback);  // dSpaceCollide, made whole
  out_ = nullptr;
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

}  // namespace collide::world
