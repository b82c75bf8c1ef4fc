#pragma once
// One scene's simulation loop:
//   forces (declared effects) -> dSpaceCollide (broad phase; the near callback gathers
//   sphere/sphere candidate pairs into a batch, other pairs go through dCollide on the
//   CPU) -> the batch through the selected backend -> contact joints -> dWorldQuickStep.
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>

#include "collide/backend.hpp"
#include "ode/ode_world.hpp"
#include "scene/scene.hpp"

namespace collide::ode {

struct StepStats {
  long long step = 0;
  std::size_t pairsTested = 0;    // sphere/sphere candidates sent to the backend
  std::size_t contacts = 0;       // of those, hits (one contact joint each)
  std::size_t otherContacts = 0;  // sphere/plane contacts found on the CPU
  std::int64_t backendNs = 0;     // wall time of the backend call
};

class Simulation {
 public:
  // Called with each step's batch before the backend sees it (e.g. to time other
  // backends on the same pairs). Must not modify the world.
  using BatchObserver = std::function<void(const SphereTable&, const PairList&, const ContactSet&)>;

  Simulation(const scene::Scene& scene, CollisionBackend& backend);

  StepStats step();
  void setBatchObserver(BatchObserver f) { observer_ = std::move(f); }
  const World& world() const { return world_; }
  long long stepsDone() const { return step_; }

 private:
  static void nearCallback(void* self, dGeomID o1, dGeomID o2);
  void near(dGeomID o1, dGeomID o2);
  void applyEffects();
  void requireSpheresInRange() const;

  const scene::Scene& scene_;
  CollisionBackend& backend_;
  World world_;
  dSurfaceParameters surface_;
  SphereTable table_;
  PairList pairs_;
  ContactSet results_;
  std::size_t otherContacts_ = 0;
  long long step_ = 0;
  BatchObserver observer_;
  // An exception in the near callback waits here: unwinding through dSpaceCollide would
  // leave the space locked, and ODE aborts when a locked space is destroyed.
  std::exception_ptr nearError_;
};

}  // namespace collide::ode
