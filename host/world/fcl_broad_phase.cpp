#include "world/fcl_broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fcl/broadphase/broadphase_SaP.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/broadphase_spatialhash.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

namespace collide::world {

struct FclBroadPhase::State {
  std::vector<std::shared_ptr<fcl::Sphered>> shapes;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> raw;
  std::unique_ptr<fcl::BroadPhaseCollisionManagerd> manager;
  std::vector<std::pair<fcl::CollisionObjectd*, fcl::CollisionObjectd*>> last;  // the last findPairs's pairs
};

namespace {

std::uint32_t sphereOf(const fcl::CollisionObjectd* o) {
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(o->getUserData()) - 1);
}

bool recordPair(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  if (a->getAABB().overlap(b->getAABB()))
    static_cast<std::vector<std::pair<fcl::CollisionObjectd*, fcl::CollisionObjectd*>>*>(data)->emplace_back(a, b);
  return false;  // go on
}

// The tuned grid's cut radius (tuned_world.hpp): the (max(16, n/16)+1)-th largest, the
// largest for 32 spheres or fewer.
double cutRadius(std::vector<double> r) {
  if (r.empty()) return 1;
  const std::size_t k = r.size() <= 32 ? 0 : std::max<std::size_t>(16, r.size() / 16);
  std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(k), r.end(), std::greater<>());
  return r[k];
}

}  // namespace

const char* toString(FclManagerKind k) {
  switch (k) {
    case FclManagerKind::DynamicTree: return "tree";
    case FclManagerKind::SweepAndPrune: return "sap";
    case FclManagerKind::SpatialHash: return "hash";
  }
  return "?";
}

FclBroadPhase::FclBroadPhase(FclManagerKind kind) : kind_(kind), st_(std::make_unique<State>()) {}

FclBroadPhase::~FclBroadPhase() = default;

std::string FclBroadPhase::name() const {
  switch (kind_) {
    case FclManagerKind::DynamicTree: return "fcl tree (DynamicAABBTreeCollisionManager)";
    case FclManagerKind::SweepAndPrune: return "fcl sap (SaPCollisionManager)";
    case FclManagerKind::SpatialHash: return "fcl hash (SpatialHashingCollisionManager)";
  }
  return "fcl";
}

void FclBroadPhase::prepare(const SphereTable& s, const std::vector<std::uint32_t>& members) {
  st_->manager.reset();  // before the objects it points to
  st_->last.clear();
  st_->raw.clear();
  st_->objects.clear();
  st_->shapes.clear();
  st_->shapes.reserve(members.size());
  st_->objects.reserve(members.size());
  fcl::Vector3d lo = fcl::Vector3d::Zero(), hi = fcl::Vector3d::Zero();
  std::vector<double> radii;
  radii.reserve(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) {
    const auto m = members[k];
    auto f32 = [](double v) { return static_cast<double>(static_cast<float>(v)); };
    const double r = f32(s.r[m]);
    const fcl::Vector3d c(f32(s.x[m]), f32(s.y[m]), f32(s.z[m]));
    auto shape = std::make_shared<fcl::Sphered>(r);
    const double reach = candidateReach(r) + 0x1p-40 * c.cwiseAbs().maxCoeff();
    shape->aabb_local = fcl::AABBd(fcl::Vector3d::Constant(-reach), fcl::Vector3d::Constant(reach));
    fcl::Transform3d t = fcl::Transform3d::Identity();
    t.translation() = c;
    auto o = std::make_unique<fcl::CollisionObjectd>(shape, t);  // computes the local box: set again
    shape->aabb_local = fcl::AABBd(fcl::Vector3d::Constant(-reach), fcl::Vector3d::Constant(reach));
    o->computeAABB();
    o->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(m) + 1));
    if (k == 0) {
      lo = o->getAABB().min_;
      hi = o->getAABB().max_;
    } else {
      lo = lo.cwiseMin(o->getAABB().min_);
      hi = hi.cwiseMax(o->getAABB().max_);
    }
    radii.push_back(r);
    st_->raw.push_back(o.get());
    st_->objects.push_back(std::move(o));
    st_->shapes.push_back(std::move(shape));
  }
  switch (kind_) {
    case FclManagerKind::DynamicTree:
      st_->manager = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
      break;
    case FclManagerKind::SweepAndPrune:
      st_->manager = std::make_unique<fcl::SaPCollisionManagerd>();
      break;
    case FclManagerKind::SpatialHash: {
      // A sphere in at most 17^3 cells (FCL files an object in every cell its box meets), and
      // at most 2^20 cells along an axis, so that FCL's int cell indices stay far from overflow.
      const double rMax = radii.empty() ? 0 : *std::max_element(radii.begin(), radii.end());
      const double edge = std::max({2 * cutRadius(std::move(radii)), rMax / 8, 0x1p-20,
                                    std::ldexp((hi - lo).maxCoeff(), -20)});
      const auto buckets = static_cast<unsigned>(2 * members.size() + 1);
      // The box holds every sphere's box (an object outside is paired with everything).
      st_->manager = std::make_unique<fcl::SpatialHashingCollisionManagerd<>>(edge, lo, hi, buckets);
      break;
    }
  }
}

void FclBroadPhase::findPairs(const SphereTable& s, const std::vector<std::uint32_t>& members, PairList& out) {
  (void)s;
  if (!st_->manager || st_->objects.size() != members.size())
    throw std::logic_error("FclBroadPhase::findPairs before prepare on these members");
  if (st_->manager->size() != 0) throw std::logic_error("FclBroadPhase::findPairs twice after one prepare");
  st_->last.clear();
  st_->manager->registerObjects(st_->raw);
  st_->manager->setup();
  st_->manager->collide(&st_->last, &recordPair);
  for (const auto& [a, b] : st_->last) {
    const auto i = sphereOf(a), j = sphereOf(b);
    out.push(std::min(i, j), std::max(i, j));
  }
}

void FclBroadPhase::engineContacts(const SphereTable& s, PairList& out) {
  (void)s;
  const fcl::CollisionRequestd request;  // one contact at most, no details
  for (const auto& [a, b] : st_->last) {
    fcl::CollisionResultd result;
    if (fcl::collide(a, b, request, result) == 0) continue;
    const auto i = sphereOf(a), j = sphereOf(b);
    out.push(std::min(i, j), std::max(i, j));
  }
}

}  // namespace collide::world
