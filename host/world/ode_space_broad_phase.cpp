#include "world/ode_space_broad_phase.hpp"

#include <algorithm>
#include <cmath>
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
      space_(kind == OdeSpaceKind::QuadTree ? nullptr : ode::createSpace(kind)) {  // a quadtree: in prepare
  if (space_) dSpaceSetCleanup(space_, 0);  // the geoms are ours (clearGeoms)
}

OdeSpaceBroadPhase::~OdeSpaceBroadPhase() {
  clearGeoms();
  if (space_) dSpaceDestroy(space_);
}

int OdeSpaceBroadPhase::quadTreeDepth(std::size_t n, double edge, double rMedian) {
  int depth = 1;
  while (depth < 10 && std::ldexp(1.0, 2 * (depth + 1)) <= static_cast<double>(n) / 8 &&
         std::ldexp(edge, -(depth + 1)) >= 8 * rMedian)
    ++depth;
  return depth;
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
  bool fresh = geoms_.size() != s.size() ||
               std::any_of(members.begin(), members.end(), [&](std::uint32_t m) { return !geoms_[m]; });
  if (kind_ == OdeSpaceKind::QuadTree) {
    // The root block: the members' box, padded by 1 % and 1 mm (a geom outside it stays at
    // the root, where it is tested against every other).
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    std::vector<double> radii;
    radii.reserve(members.size());
    for (std::size_t k = 0; k < members.size(); ++k) {
      const auto m = members[k];
      const double c[3] = {s.x[m], s.y[m], s.z[m]};
      for (int a = 0; a < 3; ++a) {
        lo[a] = k ? std::min(lo[a], c[a] - s.r[m]) : c[a] - s.r[m];
        hi[a] = k ? std::max(hi[a], c[a] + s.r[m]) : c[a] + s.r[m];
      }
      radii.push_back(s.r[m]);
    }
    double box[7];
    for (int a = 0; a < 3; ++a) {
      box[a] = (lo[a] + hi[a]) / 2;
      box[3 + a] = (hi[a] - lo[a]) / 2 * 1.01 + 1e-3;
    }
    double rMedian = 1;
    if (!radii.empty()) {
      std::nth_element(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2), radii.end());
      rMedian = radii[radii.size() / 2];
    }
    box[6] = quadTreeDepth(members.size(), 2 * std::max(box[3], box[4]), rMedian);
    if (!space_ || !std::equal(box, box + 7, quadBox_)) {
      clearGeoms();
      if (space_) dSpaceDestroy(space_);
      const dVector3 centre = {box[0], box[1], box[2], 0}, extents = {box[3], box[4], box[5], 0};
      space_ = dQuadTreeSpaceCreate(nullptr, centre, extents, static_cast<int>(box[6]));
      dSpaceSetCleanup(space_, 0);
      std::copy(box, box + 7, quadBox_);
      fresh = true;
    }
  }
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
