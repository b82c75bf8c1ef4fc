#include <algorithm>
#include <cstdio>
#include <limits>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli/clock_option.hpp"
#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/output_file.hpp"
#include "cli/run_report.hpp"
#include "collide/backend_factory.hpp"
#include "collide/ode_backend.hpp"
#include "collide/rtl_backend.hpp"
#include "collide/simd_backend.hpp"
#include "driver/afu_factory.hpp"
#include "link/link_presets.hpp"
#include "scene/scene.hpp"
#include "simulation/simulation.hpp"
#include "util/system_memory.hpp"
#include "world/afu_world.hpp"
#include "world/cpu_world.hpp"

namespace collide::cli {

void printTiming(std::ostream& os, std::int64_t ns, std::uint64_t pairs, std::uint64_t contacts) {
  os << std::fixed << std::setprecision(3) << ns / 1e6 << " ms total, ";
  if (pairs) os << std::setprecision(1) << static_cast<double>(ns) / pairs << " ns/pair, ";
  else os << "- ns/pair, ";
  if (contacts) os << std::setprecision(1) << static_cast<double>(ns) / contacts << " ns/collision";
  else os << "- ns/collision";
}

void printTimeSplit(std::ostream& os, const RunTotals& t, double narrowNs, const std::string& narrowWhat,
                    long long steps, double engineBroadNs, const std::string& broadWhat) {
  const double total = static_cast<double>(t.stepNs - t.backendNs) + narrowNs + engineBroadNs;
  const double broad = static_cast<double>(t.broadNs) + engineBroadNs;
  const double other = total - broad - static_cast<double>(t.otherNarrowNs + t.jointsNs + t.solverNs) - narrowNs;
  os << "time split   : " << std::fixed << std::setprecision(3) << total / 1e6 << " ms in " << steps << " steps ("
     << std::setprecision(1) << (steps ? total / 1e3 / static_cast<double>(steps) : 0.0) << " us a step)\n";
  auto line = [&](const char* what, double ns, const std::string& note) {
    os << "  " << std::left << std::setw(24) << what << std::right << std::setw(12) << std::setprecision(3) << ns / 1e6
       << " ms  " << std::setw(5) << std::setprecision(1) << (total > 0 ? 100.0 * ns / total : 0.0) << " %" << note << "\n";
  };
  line("broad phase", broad, "  (" + broadWhat + ")");
  line("narrow, sphere/sphere", narrowNs, "  (" + narrowWhat + ")");
  line("narrow, sphere/plane", static_cast<double>(t.otherNarrowNs), "  (dCollide on the CPU)");
  line("contact joints", static_cast<double>(t.jointsNs), "");
  line("solver", static_cast<double>(t.solverNs), "  (dWorldQuickStep)");
  line("other", other, "  (effects, range checks, the sphere table)");
}

namespace {

// The fastest of `repeat` timings: the least disturbed by a shared, noisy machine.
template <typename F>
std::int64_t timeNs(int repeat, F&& f) {
  std::int64_t best = std::numeric_limits<std::int64_t>::max();
  for (int k = 0; k < repeat; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min<std::int64_t>(
        best, std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

void printAfu(std::ostream& os, const AfuTotals& a, std::uint64_t pairs, std::uint64_t contacts,
              const std::string& linkName, std::int64_t wallNs) {
  const double c = a.cycleNs;
  auto line = [&](const char* what, double ns, const char* note) {
    os << "  " << std::left << std::setw(22) << what << std::right << std::fixed << std::setprecision(3)
       << std::setw(12) << ns / 1e3 << " us  " << std::setw(5) << std::setprecision(1)
       << (a.stats.modelledNs > 0 ? 100.0 * ns / a.stats.modelledNs : 0.0) << " %" << note << "\n";
  };
  os << "AFU (modelled, link " << linkName << "): " << a.runs << " runs, " << std::fixed << std::setprecision(3)
     << a.stats.modelledNs / 1e3 << " us";
  if (contacts) os << ", " << std::setprecision(1) << a.stats.modelledNs / contacts << " ns/collision";
  if (pairs) os << ", " << std::setprecision(2) << a.stats.modelledNs / pairs << " ns/pair";
  os << "\n";
  line("loading spheres", a.counters.cyclesLoading * c, "  (status counter; includes its read waits)");
  line("computing", a.counters.cyclesComputing * c, "  (cycles in which an SCPU took a pair)");
  line("waiting on reads", a.counters.cyclesWaitRead * c, "  (may overlap loading)");
  line("waiting on writes", a.counters.cyclesWaitWrite * c, "");
  if (a.counters.cyclesBroad)
    line("broad phase", a.counters.cyclesBroad * c, "  (world mode; the SCPUs compute during its last pass)");
  line("other AFU cycles", a.otherNs(), "  (total minus the lines above; negative if they overlap)");
  line("overhead", a.overheadNs(), "  (per run: transaction, CSR writes, status write, polling)");
  os << "  link bound " << std::setw(18) << std::setprecision(3) << a.stats.linkBoundNs / 1e3 << " us  ("
     << a.stats.readLines << " lines read, " << a.stats.writeLines << " written; modelled/bound "
     << std::setprecision(2) << (a.stats.linkBoundNs > 0 ? a.stats.modelledNs / a.stats.linkBoundNs : 0.0) << ")\n";
  os << "  simulated: " << a.stats.cyclesStepped << " cycles stepped, " << a.stats.cyclesSkipped << " skipped exactly, "
     << std::setprecision(3) << wallNs / 1e9 << " s wall\n";
}

}  // namespace

namespace {

// --- load: the scene with the command line's overrides ---------------------------------------
scene::Scene loadRunScene(const RunOptions& o) {
  scene::Scene sc = scene::loadScene(o.scene);
  if (o.backend) sc.backend = *o.backend;
  if (o.steps) sc.steps = *o.steps;
  if (o.link) sc.link = link::presetParams(*o.link);
  // A scene that cannot fit is refused before ODE allocates it (bench/results/scale).
  if (const auto avail = util::availableMemoryBytes()) {
    const bool hash = sc.offload == scene::Scene::Offload::Pairs && sc.space == limits::OdeSpaceKind::Hash;
    const auto why = limits::memoryRefusal(static_cast<long long>(sc.spheres.size()),
                                           hash ? limits::OdeSpaceKind::Hash : limits::OdeSpaceKind::SweepAndPrune, *avail);
    if (!why.empty())
      throw std::invalid_argument("scene " + sc.name + ": " + why + "; run it on a larger machine" +
                                  (hash ? ", or declare \"collision\": {\"space\": \"sap\"}" : ""));
  }
  return sc;
}

// --- backend: what computes the sphere/sphere pairs --------------------------------------------
// A pair backend, or with offload "world" an engine that does the whole sphere/sphere collision.
struct Engines {
  std::unique_ptr<CollisionBackend> backend;
  std::unique_ptr<world::WorldEngine> engine;
  RtlBackend* rtlBackend = nullptr;      // the pair backend, when it is the AFU
  world::AfuWorld* afuWorld = nullptr;   // the world engine, when it is the AFU
  std::string name;
};

// collision.require with backend rtl: every kind named must have units on the AFU, or the run
// is refused before its first step, naming the kind and the AFU.
void refuseMissingKinds(const scene::Scene& sc) {
  if (sc.requireKinds.empty()) return;
  const driver::Manifest m = driver::afuManifest(sc.afuDir);
  std::string has;
  for (const auto& k : m.pairKinds) has += (has.empty() ? "" : ", ") + k;
  const std::string afu = sc.afuDir.empty() ? "built in (" + driver::builtInAfuPreset() + ")" : sc.afuDir.string();
  for (const auto& k : sc.requireKinds)
    if (std::find(m.pairKinds.begin(), m.pairKinds.end(), k) == m.pairKinds.end())
      throw std::invalid_argument("scene " + sc.name + ": collision.require names " + k + ", but the AFU " + afu +
                                  " has units for " + has + " only (its manifest's afu.pairKinds; docs/pair-kinds.md)");
}

Engines makeEngines(const scene::Scene& sc, const RunOptions& o, bool rtl) {
  BackendRequest req{sc.backend, sc.afuDir, sc.link, {}, {}};
  req.driver.skipIdle = !o.noSkip;
  req.port.traceFile = o.trace;
  if (o.wallLimit) req.port.wallLimitS = *o.wallLimit;
  else if (sc.wallLimitS) req.port.wallLimitS = *sc.wallLimitS;
  if (!o.trace.empty() && !rtl) throw std::invalid_argument("--trace needs --backend rtl");
  const bool worldOffload = sc.offload == scene::Scene::Offload::World;
  if (worldOffload && sc.backend != "simd" && sc.backend != "rtl")
    throw std::invalid_argument("scene " + sc.name + ": collision.offload \"world\" needs backend simd or rtl, not " +
                                sc.backend + " (the world engines are our grid with the binary32 kernel and the AFU)");
  Engines e;
  if (!worldOffload) {
    e.backend = makeBackend(req);  // rtl without an AFU throws AfuUnavailable here
  } else if (rtl) {
    driver::AfuPortOptions port = req.port;  // --trace, --wall-limit; the trace's clock is the link's
    port.clockMHz = sc.link.clockMHz;
    auto a = std::make_unique<world::AfuWorld>(sc.afuDir, sc.link, port, req.driver);  // --no-skip
    e.afuWorld = a.get();
    e.engine = std::move(a);
  } else {
    e.engine = std::make_unique<world::CpuWorld>();
  }
  e.rtlBackend = dynamic_cast<RtlBackend*>(e.backend.get());
  e.name = e.backend ? e.backend->name() : sc.backend + " (offload world: " + e.engine->name() + ")";
  return e;
}

// The same pairs through ODE's collider and the simd batch in binary32 and binary64, timed
// each step: the CPU's price of precision beside the AFU's. It watches the simulation's
// batches, so it is made before the simulation and outlives it.
class CpuPeers {
 public:
  struct Step {
    std::int64_t odeNs = 0, simdNs = 0, simd64Ns = 0;
    std::uint64_t mismatch = 0, mismatch64 = 0;  // pairs where simd (simd64) and ODE disagree on hit
  };
  explicit CpuPeers(int repeat) : repeat_(repeat) {}
  void watch(sim::Simulation& sim) {
    sim.setBatchObserver([this, &sim](const SphereTable& t, const PairList& p, const ContactSet&) {
      const OdeGeomBinding geoms(&ode_, sim.world().sphereGeoms());  // ODE's collider on the world's own geoms
      last_.odeNs = timeNs(repeat_, [&] { ode_.collide(t, p, odeOut_); });
      last_.simdNs = timeNs(repeat_, [&] { simd_.collide(t, p, simdOut_); });
      last_.simd64Ns = timeNs(repeat_, [&] { simd64_.collide(t, p, simd64Out_); });
      last_.mismatch = last_.mismatch64 = 0;
      for (std::size_t k = 0; k < p.size(); ++k) {
        last_.mismatch += odeOut_.hit[k] != simdOut_.hit[k];
        last_.mismatch64 += odeOut_.hit[k] != simd64Out_.hit[k];  // 0: the same arithmetic as ODE's
      }
    });
  }
  const Step& last() const { return last_; }

 private:
  int repeat_;
  OdeBackend ode_;
  SimdBackend simd_, simd64_{LinkFormat::Binary64};
  ContactSet odeOut_, simdOut_, simd64Out_;
  Step last_;
};

// --- step: the run's steps, summed, one CSV row and (--per-step) one line each ----------------
struct Totals {
  RunTotals run;
  AfuTotals afu;
};

void writeCsvHeader(std::ostream& csv, bool rtl) {
  csv << "step,pairs,contacts,other_contacts,backend_ns,ode_ns,simd_ns,simd64_ns,hit_mismatches";
  if (rtl) csv << ",afu_runs,afu_modelled_ns,afu_cycles,afu_load,afu_compute,afu_wait_rd,afu_wait_wr";
  csv << ",broad_ns,plane_narrow_ns,joints_ns,solver_ns,step_ns,kinetic_j,max_depth_m,escaped\n";
}

void addStep(RunTotals& tot, const sim::StepStats& st, const CpuPeers::Step& cpu) {
  tot.pairs += st.pairsTested;
  tot.contacts += st.contacts;
  tot.otherContacts += st.otherContacts;
  tot.otherPairs += st.otherPairs;
  tot.backendNs += st.backendNs;
  tot.odeNs += cpu.odeNs;
  tot.simdNs += cpu.simdNs;
  tot.simd64Ns += cpu.simd64Ns;
  tot.hitMismatches += cpu.mismatch;
  tot.hit64Mismatches += cpu.mismatch64;
  tot.broadNs += st.broadNs;
  tot.otherNarrowNs += st.otherNarrowNs;
  tot.jointsNs += st.jointsNs;
  tot.solverNs += st.solverNs;
  tot.stepNs += st.stepNs;
  tot.worldBroadNs += st.worldBroadNs;
  tot.worldNarrowNs += st.worldNarrowNs;
  tot.maxKineticJ = std::max(tot.maxKineticJ, st.kineticJ);
  tot.lastKineticJ = st.kineticJ;
  tot.maxDepthM = std::max(tot.maxDepthM, st.maxDepthM);
  tot.maxEscaped = std::max(tot.maxEscaped, st.escaped);
}

void printStep(std::ostream& os, const sim::StepStats& st, const CpuPeers::Step& cpu, const Engines& e,
               const RtlBatchStats* afu) {
  os << "step " << st.step << ": " << st.pairsTested << " pairs, " << st.contacts << " contacts"
     << (st.otherContacts ? " (+" + std::to_string(st.otherContacts) + " plane)" : "");
  if (!e.engine) os << ", ode " << cpu.odeNs << " ns, simd " << cpu.simdNs << " ns, simd64 " << cpu.simd64Ns << " ns";
  if (afu) os << ", AFU " << std::fixed << std::setprecision(0) << afu->stats.modelledNs << " ns modelled";
  if (e.engine)
    os << ", world engine: broad " << st.worldBroadNs << " ns, rest " << st.worldNarrowNs << " ns"
       << (e.engine->modelled() ? " modelled" : " measured");
  os << "\n";
}

void writeCsvRow(std::ostream& csv, const sim::StepStats& st, const CpuPeers::Step& cpu, const RtlBatchStats* afu) {
  csv << st.step << ',' << st.pairsTested << ',' << st.contacts << ',' << st.otherContacts << ',' << st.backendNs << ','
      << cpu.odeNs << ',' << cpu.simdNs << ',' << cpu.simd64Ns << ',' << cpu.mismatch;
  if (afu)
    csv << ',' << afu->runs << ',' << std::fixed << std::setprecision(1) << afu->stats.modelledNs << ','
        << afu->counters.cyclesTotal << ',' << afu->counters.cyclesLoading << ',' << afu->counters.cyclesComputing
        << ',' << afu->counters.cyclesWaitRead << ',' << afu->counters.cyclesWaitWrite;
  csv << ',' << st.broadNs << ',' << st.otherNarrowNs << ',' << st.jointsNs << ',' << st.solverNs << ',' << st.stepNs
      << ',' << std::defaultfloat << std::setprecision(9) << st.kineticJ << ',' << st.maxDepthM << ',' << st.escaped
      << '\n';
}

Totals runSteps(const scene::Scene& sc, const RunOptions& o, bool rtl, sim::Simulation& sim, const Engines& e,
                const CpuPeers& cpu, OutputFile* csvFile) {
  Totals t;
  if (csvFile) writeCsvHeader(csvFile->stream(), rtl);
  for (long long s = 0; s < sc.steps; ++s) {
    const auto st = sim.step();
    addStep(t.run, st, cpu.last());
    // This step's AFU calls: the rtl backend's batch, or the world engine's run.
    RtlBatchStats stepAfu;
    if (e.rtlBackend) stepAfu = e.rtlBackend->lastBatch();
    if (e.afuWorld) stepAfu.add(e.afuWorld->lastRun().run.status, e.afuWorld->lastRun().run.stats, e.afuWorld->lastRun().attempts);
    if (rtl) { t.afu.add(stepAfu); t.afu.cycleNs = sc.link.cycleNs(); }
    const RtlBatchStats* afu = rtl ? &stepAfu : nullptr;
    if (o.perStep) printStep(std::cout, st, cpu.last(), e, afu);
    if (csvFile) writeCsvRow(csvFile->stream(), st, cpu.last(), afu);
  }
  if (csvFile) csvFile->commit();
  return t;
}

// --- report: the totals on stdout, the final positions and the JSON summary -------------------
void printTotals(std::ostream& os, const scene::Scene& sc, bool rtl, const Engines& e, const Totals& t) {
  const RunTotals& tot = t.run;
  os << "pairs tested : " << tot.pairs << " sphere/sphere candidates from the broad phase"
     << (e.engine ? " (the world engine's own)" : "") << "\n"
     << "contacts     : " << tot.contacts << " sphere/sphere";
  if (sc.groundZ || !sc.planes.empty()) os << " (+" << tot.otherContacts << " sphere/plane on the CPU)";
  os << "\n";
  os << "physics      : kinetic energy at most " << std::defaultfloat << std::setprecision(4) << tot.maxKineticJ
     << " J (last step " << tot.lastKineticJ << " J), deepest contact " << tot.maxDepthM * 1e3 << " mm, "
     << tot.maxEscaped << " spheres through a plane at most\n";
  if (!e.engine) {  // the observer's comparison runs on the pairs path only
    os << "ODE collider : ";
    printTiming(os, tot.odeNs, tot.pairs, tot.contacts);
    os << "  (dCollide on the world's dSphere geoms, binary64)\nsimd batch   : ";
    printTiming(os, tot.simdNs, tot.pairs, tot.contacts);
    os << "  (gather + binary32 SoA kernel)\nsimd64 batch : ";
    printTiming(os, tot.simd64Ns, tot.pairs, tot.contacts);
    os << "  (gather + binary64 SoA kernel: ODE's arithmetic, vectorized)\n"
       << "simd vs ode  : " << tot.hitMismatches << " pairs disagree on hit (simd64: " << tot.hit64Mismatches << ")\n";
  }
  const std::string odeBroad = std::string("dSpaceCollide, ODE's ") +
                               (sc.space == limits::OdeSpaceKind::SweepAndPrune ? "sweep-and-prune space" : "hash space");
  if (e.engine) {
    // The engine's own account: the broad phase apart, the rest as the narrow phase.
    const std::string how = e.engine->modelled() ? "modelled, link " + sc.link.name : std::string("measured");
    if (e.afuWorld) printAfu(os, t.afu, tot.pairs, tot.contacts, sc.link.name, tot.backendNs);
    printTimeSplit(os, tot, static_cast<double>(tot.worldNarrowNs), e.engine->name() + ", " + how, sc.steps,
                   static_cast<double>(tot.worldBroadNs),
                   e.engine->name() + "'s broad phase, " + how + "; planes: every sphere, on the CPU");
  } else if (rtl) {
    printAfu(os, t.afu, tot.pairs, tot.contacts, sc.link.name, tot.backendNs);
    printTimeSplit(os, tot, t.afu.stats.modelledNs,
                   "the AFU, modelled, link " + sc.link.name + "; in place of the co-simulation's wall time", sc.steps, 0,
                   odeBroad);
  } else {
    os << "backend " << e.backend->name() << "  : ";
    printTiming(os, tot.backendNs, tot.pairs, tot.contacts);
    os << "  (the backend that drove the simulation)\n";
    printTimeSplit(os, tot, static_cast<double>(tot.backendNs), "backend " + e.backend->name() + ", measured", sc.steps,
                   0, odeBroad);
  }
}

void writePositions(OutputFile& posFile, const sim::Simulation& sim) {  // binary64 as ODE holds them, %a so nothing is lost
  std::ostream& pos = posFile.stream();
  pos << "sphere,x,y,z\n";
  const auto& w = sim.world();
  char buf[128];
  for (std::size_t k = 0; k < w.sphereCount(); ++k) {
    const dReal* q = dBodyGetPosition(w.sphereBody(k));
    std::snprintf(buf, sizeof buf, "%zu,%a,%a,%a\n", k, static_cast<double>(q[0]), static_cast<double>(q[1]),
                  static_cast<double>(q[2]));
    pos << buf;
  }
  posFile.commit();
}

void writeSummary(OutputFile& summaryFile, const scene::Scene& sc, const RunOptions& o, bool rtl, const Engines& e,
                  const Totals& t, const std::optional<driver::ClockChoice>& clock) {
  const RunTotals& tot = t.run;
  const AfuTotals& afu = t.afu;
  nlohmann::json j;
  j["scene"] = sc.name;
  j["spheres"] = sc.spheres.size();
  j["steps"] = sc.steps;
  j["backend"] = e.backend ? e.backend->name() : sc.backend;
  j["offload"] = e.engine ? "world" : "pairs";
  j["pairs"] = tot.pairs;
  j["contacts"] = tot.contacts;
  // Where each pair kind went (docs/pair-kinds.md): sphere/sphere to the backend, sphere/plane
  // to ODE's own dCollide on the CPU (no AFU has sphere/plane units yet).
  j["pair_kinds"] = {{"sphere-sphere", {{"on", j["backend"]}, {"pairs", tot.pairs}, {"contacts", tot.contacts}}},
                     {"sphere-plane", {{"on", "ode (dCollide on the CPU)"}, {"pairs", tot.otherPairs},
                                       {"contacts", tot.otherContacts}, {"narrow_ns", tot.otherNarrowNs}}}};
  j["ode_ns"] = tot.odeNs;
  j["simd_ns"] = tot.simdNs;
  j["simd64_ns"] = tot.simd64Ns;
  j["backend_wall_ns"] = tot.backendNs;
  j["simd_ode_hit_mismatches"] = tot.hitMismatches;
  j["simd64_ode_hit_mismatches"] = tot.hit64Mismatches;
  j["cpu_repeat"] = o.cpuRepeat;
  j["physics"] = {{"max_kinetic_j", tot.maxKineticJ}, {"last_kinetic_j", tot.lastKineticJ},
                  {"max_depth_m", tot.maxDepthM}, {"max_escaped", tot.maxEscaped}};
  // Where the steps' wall time went; narrow_ns is the backend's wall time (rtl: the
  // co-simulation's), narrow_modelled_ns the AFU's modelled time.
  j["time_split"] = {{"broad_ns", tot.broadNs},         {"narrow_ns", tot.backendNs},
                     {"plane_narrow_ns", tot.otherNarrowNs}, {"joints_ns", tot.jointsNs},
                     {"solver_ns", tot.solverNs},       {"step_ns", tot.stepNs}};
  if (rtl) j["time_split"]["narrow_modelled_ns"] = afu.stats.modelledNs;
  if (e.engine) {  // the engine's own account (modelled on the AFU), beside its wall time above
    j["time_split"]["world_broad_ns"] = tot.worldBroadNs;
    j["time_split"]["world_narrow_ns"] = tot.worldNarrowNs;
  }
  if (rtl) {
    j["afu"] = {{"preset", driver::builtInAfuPreset()},
                {"link", sc.link.name},
                {"clock_mhz", sc.link.clockMHz},
                {"clock", clock->toJson()},
                {"runs", afu.runs},
                {"modelled_ns", afu.stats.modelledNs},
                {"cycle_ns", afu.cycleNs},
                {"cycles_total", afu.counters.cyclesTotal},
                {"loading_ns", afu.counters.cyclesLoading * afu.cycleNs},
                {"computing_ns", afu.counters.cyclesComputing * afu.cycleNs},
                {"wait_read_ns", afu.counters.cyclesWaitRead * afu.cycleNs},
                {"wait_write_ns", afu.counters.cyclesWaitWrite * afu.cycleNs},
                {"other_ns", afu.otherNs()},
                {"overhead_ns", afu.overheadNs()},
                {"read_lines", afu.stats.readLines},
                {"write_lines", afu.stats.writeLines},
                {"link_bound_ns", afu.stats.linkBoundNs},
                {"cycles_stepped", afu.stats.cyclesStepped},
                {"cycles_skipped", afu.stats.cyclesSkipped}};
  }
  summaryFile.stream() << j.dump(2) << "\n";
  summaryFile.commit();
}

}  // namespace

// Load, backend, step, report.
int runScene(const RunOptions& o) {
  return reportErrors("collide run", [&]() -> int {
    scene::Scene sc = loadRunScene(o);
    const bool rtl = sc.backend == "rtl";
    std::optional<driver::ClockChoice> clock;
    if (rtl) clock = applyClockOption(sc.link, o.clockMHz);  // over the scene's link or --link
    else refuseClockOption(o.clockMHz, "backend " + sc.backend);
    const Engines e = makeEngines(sc, o, rtl);
    if (rtl) refuseMissingKinds(sc);

    std::cout << "scene " << sc.name << ": " << sc.spheres.size() << " spheres, " << sc.steps << " steps, dt " << sc.dt
              << ", backend " << e.name << ", link " << (rtl ? sc.link.name : std::string("not simulated (CPU backend)"));
    if (rtl)
      std::cout << ", AFU " << (driver::builtInAfuPreset().empty() ? "?" : driver::builtInAfuPreset()) << " at "
                << sc.link.clockMHz << " MHz";
    std::cout << "\n";
    if (clock) std::cout << "  " << clock->describe() << "\n";

    CpuPeers cpu(o.cpuRepeat);
    auto sim = e.backend ? std::make_unique<sim::Simulation>(sc, *e.backend) : std::make_unique<sim::Simulation>(sc, *e.engine);
    cpu.watch(*sim);

    // Every output is opened before the run, so a bad path fails at once; each goes to a
    // temporary file that replaces the named one only when complete (OutputFile).
    auto open = [](const std::string& f) -> std::unique_ptr<OutputFile> { return f.empty() ? nullptr : std::make_unique<OutputFile>(f); };
    const auto csvFile = open(o.out), posFile = open(o.positions), summaryFile = open(o.summary);

    const Totals t = runSteps(sc, o, rtl, *sim, e, cpu, csvFile.get());
    printTotals(std::cout, sc, rtl, e, t);
    if (posFile) writePositions(*posFile, *sim);
    if (summaryFile) writeSummary(*summaryFile, sc, o, rtl, e, t, clock);
    return 0;
  });
}

}  // namespace collide::cli
