#include "world/bullet_broad_phase.hpp"

#include <algorithm>
#include <stdexcept>

#include <btBulletCollisionCommon.h>

namespace collide::world {

namespace {

// A sphere whose box is its binary32 reach (engine_broad_phase.hpp) rather than its radius;
// everything else, Bullet's narrow phase included, sees the sphere itself.
class ReachSphere final : public btSphereShape {
 public:
  ReachSphere(btScalar radius, btScalar reach) : btSphereShape(radius), reach_(reach) {}
  void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override {
    const btVector3 extent(reach_, reach_, reach_);
    aabbMin = t.getOrigin() - extent;
    aabbMax = t.getOrigin() + extent;
  }

 private:
  btScalar reach_;
};

std::uint32_t sphereOf(const btCollisionObject* o) { return static_cast<std::uint32_t>(o->getUserIndex()); }

}  // namespace

const char* toString(BulletBroadKind k) { return k == BulletBroadKind::Dbvt ? "dbvt" : "sap"; }

BulletBroadPhase::BulletBroadPhase(BulletBroadKind kind, std::size_t maxNarrowSweep)
    : kind_(kind), maxNarrowSweep_(std::min(maxNarrowSweep, kMaxNarrowSweep)) {}

BulletBroadPhase::~BulletBroadPhase() { release(); }

std::string BulletBroadPhase::name() const {
  if (kind_ == BulletBroadKind::Dbvt) return "bullet dbvt (btDbvtBroadphase)";
  return wide_ ? "bullet sap (bt32BitAxisSweep3)" : "bullet sap (btAxisSweep3)";
}

void BulletBroadPhase::release() {
  if (world_) {
    // Bullet removes a proxy by scanning every pair for it; with the pairs gone first (each
    // O(1) from the back, freeing its algorithm and manifold) no scan finds any.
    btOverlappingPairCache* cache = world_->getPairCache();
    for (int k = cache->getNumOverlappingPairs() - 1; k >= 0; --k) {
      btBroadphasePair& p = cache->getOverlappingPairArray()[k];
      cache->removeOverlappingPair(p.m_pProxy0, p.m_pProxy1, dispatcher_.get());
    }
    // The proxies go without removeCollisionObject (a linear search of the world's objects
    // each): the dbvt's one by one (O(log n) each); the axis sweep's are let go, since it
    // moves a removed handle's edges to the end of each axis (O(n) each) and its handles
    // live in its own array, freed with it. The world then finds no proxy to destroy.
    for (auto& o : objects_) {
      btBroadphaseProxy* h = o->getBroadphaseHandle();
      if (!h) continue;
      o->setBroadphaseHandle(nullptr);
      if (kind_ == BulletBroadKind::Dbvt) broadphase_->destroyProxy(h, dispatcher_.get());
    }
  }
  // The world before its broad phase and dispatcher.
  world_.reset();
  broadphase_.reset();
  dispatcher_.reset();
  config_.reset();
  objects_.clear();
  shapes_.clear();
}

void BulletBroadPhase::prepare(const SphereTable& s, const std::vector<std::uint32_t>& members) {
  release();
  config_ = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
  shapes_.reserve(members.size());
  objects_.reserve(members.size());
  // Binary32 values, as the simd kernel's gather rounds them (btScalar is float here).
  btVector3 lo(0, 0, 0), hi(0, 0, 0);
  for (std::size_t k = 0; k < members.size(); ++k) {
    const auto m = members[k];
    const btScalar r = static_cast<float>(s.r[m]);
    const btScalar reach = static_cast<float>(candidateReach(r));
    const btVector3 c(static_cast<float>(s.x[m]), static_cast<float>(s.y[m]), static_cast<float>(s.z[m]));
    shapes_.push_back(std::make_unique<ReachSphere>(r, reach));
    auto o = std::make_unique<btCollisionObject>();
    o->setCollisionShape(shapes_.back().get());
    btTransform t;
    t.setIdentity();
    t.setOrigin(c);
    o->setWorldTransform(t);
    o->setUserIndex(static_cast<int>(m));
    objects_.push_back(std::move(o));
    const btVector3 e(reach, reach, reach);
    if (k == 0) {
      lo = c - e;
      hi = c + e;
    } else {
      lo.setMin(c - e);
      hi.setMax(c + e);
    }
  }
  wide_ = false;
  if (kind_ == BulletBroadKind::Dbvt) {
    broadphase_ = std::make_unique<btDbvtBroadphase>();
  } else {
    // The spheres' box, grown past updateAabbs' threshold (a box outside is clamped to it).
    const btVector3 pad = (hi - lo) * btScalar(0.01) + btVector3(1, 1, 1);
    wide_ = members.size() > maxNarrowSweep_;
    // No raycast accelerator (a second, dbvt, broad phase): nothing here casts rays.
    if (wide_)
      broadphase_ = std::make_unique<bt32BitAxisSweep3>(lo - pad, hi + pad, static_cast<unsigned>(members.size()), nullptr, true);
    else
      broadphase_ = std::make_unique<btAxisSweep3>(lo - pad, hi + pad, static_cast<unsigned short>(std::max<std::size_t>(2, members.size())),
                                                   nullptr, true);
  }
  world_ = std::make_unique<btCollisionWorld>(dispatcher_.get(), broadphase_.get(), config_.get());
}

void BulletBroadPhase::findPairs(const SphereTable& s, const std::vector<std::uint32_t>& members, PairList& out) {
  (void)s;
  if (!world_ || objects_.size() != members.size())
    throw std::logic_error("BulletBroadPhase::findPairs before prepare on these members");
  if (!objects_.empty() && objects_.front()->getBroadphaseHandle())
    throw std::logic_error("BulletBroadPhase::findPairs twice after one prepare");
  for (auto& o : objects_) world_->addCollisionObject(o.get());
  // performDiscreteCollisionDetection, up to its narrow phase.
  world_->updateAabbs();
  world_->computeOverlappingPairs();
  btOverlappingPairCache* cache = world_->getPairCache();
  const int n = cache->getNumOverlappingPairs();
  const btBroadphasePair* pairs = cache->getOverlappingPairArrayPtr();
  for (int k = 0; k < n; ++k) {
    const auto a = sphereOf(static_cast<const btCollisionObject*>(pairs[k].m_pProxy0->m_clientObject));
    const auto b = sphereOf(static_cast<const btCollisionObject*>(pairs[k].m_pProxy1->m_clientObject));
    out.push(std::min(a, b), std::max(a, b));
  }
}

void BulletBroadPhase::engineContacts(const SphereTable& s, PairList& out) {
  (void)s;
  if (!world_) throw std::logic_error("BulletBroadPhase::engineContacts before findPairs");
  // performDiscreteCollisionDetection's last step.
  dispatcher_->dispatchAllCollisionPairs(world_->getPairCache(), world_->getDispatchInfo(), dispatcher_.get());
  const int n = dispatcher_->getNumManifolds();
  for (int k = 0; k < n; ++k) {
    const btPersistentManifold* m = dispatcher_->getManifoldByIndexInternal(k);
    if (m->getNumContacts() == 0) continue;
    const auto a = sphereOf(m->getBody0()), b = sphereOf(m->getBody1());
    out.push(std::min(a, b), std::max(a, b));
  }
}

}  // namespace collide::world
