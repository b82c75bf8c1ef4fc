#pragma once
// One scene's simulation loop:
//   forces (declared effects) -> dSpaceCollide (broad phase; the near callback gathers
//   sphere/sphere candidate pairs into a batch and the other pairs into a list) -> dCollide on
//   the other pairs (sphere/plane, CPU) -> the batch through the selected backend -> contact
//   joints (sphere/plane first, as ODE found them) -> dWorldQuickStep. Each stage is timed.
// With a world engine (a scene's "collision": {"offload": "world"}) ODE's space is not
// asked: every plane meets every sphere (dCollide on the CPU), and the engine does the whole
// sphere/sphere collision, broad phase included.
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <utility>
#include <vector>

#include "collide/backend.hpp"
#include "collide/ode_backend.hpp"
#include "ode/ode_world.hpp"
#include "scene/scene.hpp"
#include "world/world_engine.hpp"

namespace collide::sim {

struct StepStats {
  long long step = 0;
  std::size_t pairsTested = 0;    // sphere/sphere candidates sent to the backend
  std::size_t contacts = 0;       // of those, hits (one contact joint each)
  std::size_t otherPairs = 0;     // sphere/plane pairs ODE's space found, collided on the CPU
  std::size_t otherContacts = 0;  // sphere/plane contacts found on the CPU
  std::int64_t backendNs = 0;     // wall time of the backend call (the sphere/sphere narrow phase)
  // Where the step's wall time went (the observer's own work excluded):
  std::int64_t broadNs = 0;       // dSpaceCollide (with the near callback, which only records pairs)
  std::int64_t otherNarrowNs = 0; // dCollide on the sphere/plane pairs
  std::int64_t jointsNs = 0;      // creating the contact joints
  std::int64_t solverNs = 0;      // dWorldQuickStep and emptying the contact group
  std::int64_t stepNs = 0;        // the whole step
  // World engine only: its own account of the sphere/sphere collision (backendNs is its wall
  // time): the broad phase and the rest, measured on the CPU, modelled on the AFU.
  std::int64_t worldBroadNs = 0, worldNarrowNs = 0;
  // The physics after the step, for stability studies (bench/stability): whether a scene at
  // rest stays at rest in a given arithmetic.
  double kineticJ = 0;        // translational + rotational kinetic energy of the spheres
  double maxDepthM = 0;       // the deepest contact this step (sphere/sphere hits and sphere/plane)
  std::size_t escaped = 0;    // spheres whose centre lies beyond a declared plane (through a wall)
};

class Simulation {
 public:
  // Called with each step's batch before the backend sees it (e.g. to time other
  // backends on the same pairs). Must not modify the world.
  using BatchObserver = std::function<void(const SphereTable&, const PairList&, const ContactSet&)>;

  Simulation(const scene::Scene& scene, CollisionBackend& backend);
  // The whole sphere/sphere collision by `engine` (no batch observer is called).
  Simulation(const scene::Scene& scene, world::WorldEngine& engine);

  StepStats step();
  void setBatchObserver(BatchObserver f) { observer_ = std::move(f); }
  const ode::World& world() const { return world_; }
  long long stepsDone() const { return step_; }

 private:
  static void nearCallback(void* self, dGeomID o1, dGeomID o2);
  void near(dGeomID o1, dGeomID o2);
  void applyEffects();
  void requireSpheresInRange() const;
  void pairPlanesWithSpheres();
  void collideWorld(StepStats& st);
  void measureState(StepStats& st) const;

  const scene::Scene& scene_;
  CollisionBackend* backend_ = nullptr;  // the pairs path...
  world::WorldEngine* engine_ = nullptr; // ...or the world path
  OdeBackend* odeBackend_ = nullptr;     // backend_ if it is the ode one: it collides the world's own geoms
  ode::World world_;
  dSurfaceParameters surface_;
  SphereTable table_;
  PairList pairs_;
  std::vector<std::pair<dGeomID, dGeomID>> otherPairs_;  // not sphere/sphere: ODE collides them
  std::vector<dContactGeom> otherContacts_;
  ContactSet results_;
  world::WorldContacts worldOut_;
  world::WorldTiming worldTime_;
  long long step_ = 0;
  BatchObserver observer_;
  // An exception in the near callback waits here: unwinding through dSpaceCollide would
  // leave the space locked, and ODE aborts when a locked space is destroyed.
  std::exception_ptr nearError_;
};

}  // namespace collide::sim
