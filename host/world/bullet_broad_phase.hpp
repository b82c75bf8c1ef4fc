#pragma once
// Bullet 3's broad phase for world mode (`collide spheres --backend bullet`): the spheres as
// btCollisionObjects with btSphereShapes in a btCollisionWorld over btDbvtBroadphase
// (`--space dbvt`, two dynamic AABB trees) or an axis sweep (`--space sap`: btAxisSweep3, or
// bt32BitAxisSweep3 above 32,766 spheres, over the spheres' box). Built only when CMake finds
// Bullet (COLLIDE_HAVE_BULLET).
//
// findPairs is the broad half of btCollisionWorld::performDiscreteCollisionDetection on a world
// built from scratch: addCollisionObject for every sphere (its proxy inserted), updateAabbs
// and computeOverlappingPairs; the pair cache's pairs are the candidates, which the simd kernel
// decides. engineContacts is its third step, dispatchAllCollisionPairs (Bullet's
// btSphereSphereCollisionAlgorithm, binary32), and reads the manifolds that hold a point.
//
// Margins and conventions: a btSphereShape is a point with its whole radius as collision
// margin (getMargin() is the radius; setMargin does not change its size), so no margin
// inflates it. Each shape here reports a box of candidateReach (engine_broad_phase.hpp), and
// updateAabbs adds gContactBreakingThreshold (Bullet's default 0.02 m) on every side: both
// only add candidates. Bullet's distance is negative in penetration; its sphere algorithm adds
// a point when |c1 - c2| <= r1 + r2 (distance <= 0, touching included), which a manifold keeps
// while the distance is at most its breaking threshold; ours is a contact unless
// d > r1 + r2 in binary32, the same rule.
#include <memory>
#include <string>
#include <vector>

#include "world/engine_broad_phase.hpp"

class btBroadphaseInterface;
class btCollisionConfiguration;
class btCollisionDispatcher;
class btCollisionObject;
class btCollisionShape;
class btCollisionWorld;

namespace collide::world {

enum class BulletBroadKind { Dbvt, AxisSweep };
const char* toString(BulletBroadKind k);

class BulletBroadPhase final : public EngineBroadPhase {
 public:
  // btAxisSweep3's 16-bit handles index 2 n + 2 edges: past this many spheres, 32-bit ones.
  static constexpr std::size_t kMaxNarrowSweep = 32766;
  // maxNarrowSweep: a lower switch to bt32BitAxisSweep3, for tests.
  explicit BulletBroadPhase(BulletBroadKind kind, std::size_t maxNarrowSweep = kMaxNarrowSweep);
  ~BulletBroadPhase() override;
  BulletBroadPhase(const BulletBroadPhase&) = delete;
  BulletBroadPhase& operator=(const BulletBroadPhase&) = delete;

  std::string name() const override;
  // Untimed: a fresh world (the axis sweep's bounds from the members' boxes), its shapes and
  // objects, not yet added.
  void prepare(const SphereTable& s, const std::vector<std::uint32_t>& members) override;
  void findPairs(const SphereTable& s, const std::vector<std::uint32_t>& members, PairList& out) override;
  void engineContacts(const SphereTable& s, PairList& out) override;
  std::string engineNarrowName() const override { return "bullet btSphereSphereCollisionAlgorithm (binary32)"; }

 private:
  void release();

  BulletBroadKind kind_;
  std::size_t maxNarrowSweep_;
  bool wide_ = false;  // the axis sweep with 32-bit handles
  std::unique_ptr<btCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btCollisionWorld> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btCollisionObject>> objects_;
};

}  // namespace collide::world
