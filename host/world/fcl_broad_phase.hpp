#pragma once
// FCL 0.7's broad-phase managers for world mode (`collide spheres --backend fcl`): the
// spheres as fcl::CollisionObjectd with fcl::Sphered (binary64) in a
// DynamicAABBTreeCollisionManager (`--space tree`), a SaPCollisionManager (`--space sap`) or a
// SpatialHashingCollisionManager (`--space hash`: the scene box is the spheres' boxes, the
// cell edge the diameter of the tuned grid's cut radius, the (max(16, n/16)+1)-th largest
// (the largest for 32 spheres or fewer), but at least 1/16 of the largest diameter and 2^-20
// of the box, and a table of 2n + 1 buckets). Built only when CMake finds FCL (COLLIDE_HAVE_FCL).
//
// findPairs registers the objects with a fresh manager, calls setup and the manager's
// self-collide with a callback that records each pair whose boxes overlap (the hash manager
// reports every pair sharing a cell; the others already test the boxes); the simd kernel
// decides them. engineContacts runs fcl::collide on the same pairs (FCL's sphere/sphere
// test, binary64: a contact when |c1 - c2| <= r1 + r2) and keeps those with a contact.
//
// Each object's box is the sphere's binary32 reach (engine_broad_phase.hpp, set as the
// geometry's local box, which is all the managers read) plus 2^-40 of the centre's largest
// coordinate, so the boxes of a binary32 hit overlap by more than FCL's binary64 rounding (the
// hash manager gives a box the cells floor(min / edge) to ceil(max / edge) - 1, so two boxes
// that only touch on a cell boundary would share none).
#include <memory>
#include <string>
#include <vector>

#include "world/engine_broad_phase.hpp"

namespace collide::world {

enum class FclManagerKind { DynamicTree, SweepAndPrune, SpatialHash };
const char* toString(FclManagerKind k);

class FclBroadPhase final : public EngineBroadPhase {
 public:
  explicit FclBroadPhase(FclManagerKind kind);
  ~FclBroadPhase() override;
  FclBroadPhase(const FclBroadPhase&) = delete;
  FclBroadPhase& operator=(const FclBroadPhase&) = delete;

  std::string name() const override;
  // Untimed: the objects (binary32 centres and radii) and an empty manager.
  void prepare(const SphereTable& s, const std::vector<std::uint32_t>& members) override;
  void findPairs(const SphereTable& s, const std::vector<std::uint32_t>& members, PairList& out) override;
  void engineContacts(const SphereTable& s, PairList& out) override;
  std::string engineNarrowName() const override { return "fcl::collide (binary64)"; }

 private:
  struct State;
  FclManagerKind kind_;
  std::unique_ptr<State> st_;
};

}  // namespace collide::world
