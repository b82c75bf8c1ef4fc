#include "simulation/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "batch/sane_ranges.hpp"
#include "ode/contact_joints.hpp"

namespace collide::sim {

Simulation::Simulation(const scene::Scene& scene, CollisionBackend& backend)
    : scene_(scene),
      backend_(&backend),
      odeBackend_(dynamic_cast<OdeBackend*>(&backend)),
      world_(scene),
      surface_(ode::surfaceFor(scene.contact)) {}

Simulation::Simulation(const scene::Scene& scene, world::WorldEngine& engine)
    : scene_(scene), engine_(&engine), world_(scene), surface_(ode::surfaceFor(scene.contact)) {}

void Simulation::nearCallback(void* self, dGeomID o1, dGeomID o2) {
  auto* sim = static_cast<Simulation*>(self);
  if (sim->nearError_) return;  // the rest of the broad phase is skipped
  try {
    sim->near(o1, o2);
  } catch (...) {
    sim->nearError_ = std::current_exception();
  }
}

// A body flung beyond the sane range (batch/sane_ranges.hpp) is a reported event, not ODE's
// assertion in the next broad phase.
void Simulation::requireSpheresInRange() const {
  for (std::size_t k = 0; k < world_.sphereCount(); ++k) {
    const dReal* p = dBodyGetPosition(world_.sphereBody(k));
    if (limits::saneCoordinate(p[0]) && limits::saneCoordinate(p[1]) && limits::saneCoordinate(p[2])) continue;
    std::ostringstream m;
    m << "step " << step_ << ": sphere " << k << " left the sane range |x|, |y|, |z| <= " << limits::kMaxCoordinateM
      << " m, at (" << p[0] << ", " << p[1] << ", " << p[2] << "), velocity ("
      << dBodyGetLinearVel(world_.sphereBody(k))[0] << ", " << dBodyGetLinearVel(world_.sphereBody(k))[1] << ", "
      << dBodyGetLinearVel(world_.sphereBody(k))[2] << ") m/s (docs/host.md, \"What reaches ODE\")";
    throw std::runtime_error(m.str());
  }
}

void Simulation::near(dGeomID o1, dGeomID o2) {
  const long i = world_.sphereIndex(o1), j = world_.sphereIndex(o2);
  if (i >= 0 && j >= 0) {  // sphere/sphere: to the batch, o1 first (normal from o2 to o1)
    pairs_.push(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
    return;
  }
  // Anything else (sphere/plane) stays on the CPU through ODE's own colliders, after the
  // broad phase, so that the two are timed apart.
  otherPairs_.emplace_back(o1, o2);
}

void Simulation::applyEffects() {
  if (!scene_.attractor) return;  // gravity is the world's own setting
  const auto& a = *scene_.attractor;
  for (std::size_t k = 0; k < world_.sphereCount(); ++k) {
    dBodyID b = world_.sphereBody(k);
    const dReal* p = dBodyGetPosition(b);
    const double d[3] = {a.point[0] - p[0], a.point[1] - p[1], a.point[2] - p[2]};
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len > 0) dBodyAddForce(b, a.force * d[0] / len, a.force * d[1] / len, a.force * d[2] / len);
  }
}

namespace {
using Clock = std::chrono::steady_clock;
std::int64_t nsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(b - a).count();
}
}  // namespace

// The world path's broad phase for planes: ODE's space is not asked, every plane meets
// every sphere (the engine finds the sphere/sphere pairs itself).
void Simulation::pairPlanesWithSpheres() {
  const int n = dSpaceGetNumGeoms(world_.space());
  for (int g = 0; g < n; ++g) {
    dGeomID geom = dSpaceGetGeom(world_.space(), g);
    if (world_.sphereIndex(geom) >= 0) continue;
    for (std::size_t k = 0; k < world_.sphereCount(); ++k) otherPairs_.emplace_back(world_.sphereGeom(k), geom);
  }
}

// The world path's sphere/sphere collision: the engine on the sphere table.
void Simulation::collideWorld(StepStats& st) {
  engine_->collide(table_, worldOut_, worldTime_);
  st.worldBroadNs = worldTime_.broadNs;
  st.worldNarrowNs = worldTime_.narrowNs + worldTime_.finishNs;
  // Every sphere passed requireSpheresInRange, so the engine's input policy rejects none.
  if (!worldOut_.badSpheres.empty())
    throw std::logic_error("internal error: the world engine rejected sphere " + std::to_string(worldOut_.badSpheres[0]) +
                           " after the range check passed it");
  st.pairsTested = worldOut_.candidates;
}

StepStats Simulation::step() {
  StepStats st;
  st.step = step_;
  const auto start = Clock::now();
  pairs_.clear();
  otherPairs_.clear();
  otherContacts_.clear();
  requireSpheresInRange();
  applyEffects();
  auto t0 = Clock::now();
  if (engine_) {
    pairPlanesWithSpheres();
  } else {
    world_.collideSpace(this, &Simulation::nearCallback);
    if (nearError_) std::rethrow_exception(std::exchange(nearError_, nullptr));
  }
  auto t1 = Clock::now();
  st.broadNs = nsBetween(t0, t1);

  for (const auto& [o1, o2] : otherPairs_) {
    dContactGeom cg[4];
    const int n = dCollide(o1, o2, 4, cg, sizeof(dContactGeom));
    otherContacts_.insert(otherContacts_.end(), cg, cg + n);
  }
  t0 = Clock::now();
  st.otherNarrowNs = nsBetween(t1, t0);

  world_.fillSphereTable(table_);
  if (engine_) {
    t0 = Clock::now();
    collideWorld(st);
    t1 = Clock::now();
  } else {
    const OdeGeomBinding geoms(odeBackend_, world_.sphereGeoms());  // bound for this step's call only
    t0 = Clock::now();
    backend_->collide(table_, pairs_, results_);
    t1 = Clock::now();
    st.pairsTested = pairs_.size();
  }
  st.backendNs = nsBetween(t0, t1);
  if (observer_ && !engine_) observer_(table_, pairs_, results_);
  const auto afterObserver = Clock::now();

  // The sphere/sphere contacts: the backend's on the batch, or the engine's (all hits).
  const PairList& pairs = engine_ ? worldOut_.pairs : pairs_;
  const ContactSet& results = engine_ ? worldOut_.contacts : results_;
  // Sphere/plane joints first: the order ODE found them in before the batch existed.
  for (const auto& g : otherContacts_) ode::addContactJoint(world_.world(), world_.contacts(), surface_, g);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (!results.hit[k]) continue;
    dContactGeom g{};
    g.pos[0] = results.px[k]; g.pos[1] = results.py[k]; g.pos[2] = results.pz[k];
    g.normal[0] = results.nx[k]; g.normal[1] = results.ny[k]; g.normal[2] = results.nz[k];
    g.depth = results.depth[k];
    g.g1 = world_.sphereGeom(pairs.i[k]);
    g.g2 = world_.sphereGeom(pairs.j[k]);
    g.side1 = g.side2 = -1;
    ode::addContactJoint(world_.world(), world_.contacts(), surface_, g);
    ++st.contacts;
    st.maxDepthM = std::max(st.maxDepthM, g.depth);
  }
  for (const auto& g : otherContacts_) st.maxDepthM = std::max(st.maxDepthM, g.depth);
  st.otherContacts = otherContacts_.size();
  st.otherPairs = otherPairs_.size();
  t0 = Clock::now();
  st.jointsNs = nsBetween(afterObserver, t0);

  dWorldQuickStep(world_.world(), scene_.dt);
  dJointGroupEmpty(world_.contacts());
  const auto end = Clock::now();
  st.solverNs = nsBetween(t0, end);
  st.stepNs = nsBetween(start, end) - nsBetween(t1, afterObserver);
  measureState(st);
  ++step_;
  return st;
}

void Simulation::measureState(StepStats& st) const {
  for (std::size_t k = 0; k < world_.sphereCount(); ++k) {
    const dBodyID b = world_.sphereBody(k);
    dMass m;
    dBodyGetMass(b, &m);
    const dReal* v = dBodyGetLinearVel(b);
    const dReal* w = dBodyGetAngularVel(b);
    // A sphere's inertia is isotropic: I[0] (row 0, column 0) is its moment about any axis.
    st.kineticJ += 0.5 * m.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
                   0.5 * m.I[0] * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    const dReal* p = dBodyGetPosition(b);
    bool out = scene_.groundZ && p[2] < *scene_.groundZ;
    for (const auto& pl : scene_.planes)
      out = out || pl.normal[0] * p[0] + pl.normal[1] * p[1] + pl.normal[2] * p[2] < pl.offset;
    st.escaped += out;
  }
}

}  // namespace collide::sim
