// collide spheres: world mode on the CPU (docs/host.md, "collide spheres").
#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "cli/clock_option.hpp"
#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/output_file.hpp"
#include "cli/spheres_csv.hpp"
#include "collide/backend_factory.hpp"
#include "collide/ode_backend.hpp"
#include "util/input_file.hpp"
#include "link/link_presets.hpp"
#include "world/afu_world.hpp"
#if COLLIDE_HAVE_BULLET
#include "world/bullet_broad_phase.hpp"
#endif
#include "world/engine_broad_phase.hpp"
#if COLLIDE_HAVE_FCL
#include "world/fcl_broad_phase.hpp"
#endif
#include "world/grid_broad_phase.hpp"
#include "world/ode_space_broad_phase.hpp"
#include "world/tuned_world.hpp"
#include "world/world_collider.hpp"

namespace collide::cli {

namespace {

struct Pipeline {
  std::unique_ptr<world::BroadPhase> broad;
  std::unique_ptr<CollisionBackend> narrow;
};

Pipeline makePipeline(const SpheresOptions& o) {
  Pipeline p;
  if (o.backend == "simd") {
    if (!o.space.empty())
      throw std::invalid_argument("--space " + o.space + " applies to --backend ode, bullet or fcl (simd has its own grid)");
    p.broad = std::make_unique<world::GridBroadPhase>();
  } else if (o.backend == "ode") {
    const std::string space = o.space.empty() ? kDefaultOdeSpace : o.space;
    if (space != "hash" && space != "sap" && space != "quadtree")
      throw std::invalid_argument("--space " + space + " is no ODE space (expected hash, sap or quadtree)");
    p.broad = std::make_unique<world::OdeSpaceBroadPhase>(space == "hash"  ? world::OdeSpaceKind::Hash
                                                          : space == "sap" ? world::OdeSpaceKind::SweepAndPrune
                                                                           : world::OdeSpaceKind::QuadTree);
  } else if (o.backend == "bullet") {
    const std::string space = o.space.empty() ? kDefaultBulletSpace : o.space;
    if (space != "dbvt" && space != "sap")
      throw std::invalid_argument("--space " + space + " is no Bullet broad phase (expected dbvt or sap)");
#if COLLIDE_HAVE_BULLET
    p.broad = std::make_unique<world::BulletBroadPhase>(space == "dbvt" ? world::BulletBroadKind::Dbvt
                                                                        : world::BulletBroadKind::AxisSweep);
#else
    throw std::invalid_argument("--backend bullet: this build has no Bullet (CMake found no pkg-config bullet)");
#endif
  } else if (o.backend == "fcl") {
    const std::string space = o.space.empty() ? kDefaultFclSpace : o.space;
    if (space != "tree" && space != "sap" && space != "hash")
      throw std::invalid_argument("--space " + space + " is no FCL manager (expected tree, sap or hash)");
#if COLLIDE_HAVE_FCL
    p.broad = std::make_unique<world::FclBroadPhase>(space == "tree"  ? world::FclManagerKind::DynamicTree
                                                     : space == "sap" ? world::FclManagerKind::SweepAndPrune
                                                                      : world::FclManagerKind::SpatialHash);
#else
    throw std::invalid_argument("--backend fcl: this build has no FCL (CMake found no package fcl)");
#endif
  } else {
    throw std::invalid_argument("unknown backend '" + o.backend + "' (expected simd, grid, ode, bullet or fcl)");
  }
  BackendRequest req;  // the construction path of `run` and `pairs` too
  // Another engine's broad phase feeds the binary32 kernel: simd's contacts.
  req.name = o.backend == "bullet" || o.backend == "fcl" ? "simd" : o.backend;
  p.narrow = makeBackend(req);
  // An ODE space with the ode narrow phase: dCollide on the space's own geoms (narrow is
  // destroyed first, so it never holds them dangling).
  auto* space = dynamic_cast<world::OdeSpaceBroadPhase*>(p.broad.get());
  if (auto* ode = dynamic_cast<OdeBackend*>(p.narrow.get()); ode && space) ode->useGeoms(&space->geoms());
  return p;
}

double us(std::int64_t ns) { return static_cast<double>(ns) / 1e3; }

void readSpheres(const SpheresOptions& o, LinkFormat format, SphereTable& spheres) {
  if (o.in == "-") {
    readSpheresCsv(std::cin, "<stdin>", format, spheres);
  } else {
    std::ifstream in = util::openInput(o.in);  // a directory says so
    readSpheresCsv(in, o.in, format, spheres);
  }
}

// A world-mode status line's cycles and grid, as the summary's `afu` object and each of its
// runs give them.
nlohmann::json statusJson(const driver::StatusLine& s) {
  const auto level = static_cast<std::int32_t>(s.worldCellLevel);
  return {{"cycles_total", s.cyclesTotal},   {"cycles_load", s.cyclesLoading},
          {"cycles_broad", s.cyclesBroad},   {"cycles_compute", s.cyclesComputing},
          {"cell_level", level},             {"cell_edge", driver::cellEdge(level)},
          {"large", s.worldLarge}};
}

// World mode on the AFU: one run a slab (all in one call through a run queue; its cycles do not
// vary), timed by the link model.
int runSpheresAfu(const SpheresOptions& o) {
  if (!o.space.empty()) throw std::invalid_argument("--space " + o.space + " applies to --backend ode, bullet or fcl (the AFU has its own grid)");
  link::LinkParams lp = link::presetParams(o.link);
  const auto clock = applyClockOption(lp, o.clockMHz);
  driver::AfuPortOptions po;
  po.clockMHz = lp.clockMHz;
  world::AfuWorld afu(o.afu, lp, po);
  OutputFile out(o.out, OutputFile::Dash::IsStdout);
  std::unique_ptr<OutputFile> summary = o.summary.empty() ? nullptr : std::make_unique<OutputFile>(o.summary);
  SphereTable spheres;
  readSpheres(o, afu.driver().options().format, spheres);
  world::WorldContacts w;
  afu.collide(spheres, w);
  writeWorldContactsCsv(out.stream(), w);
  out.commit();

  const auto& r = afu.lastRun();
  const auto& s = r.run.status;
  const double cyc = afu.cycleNs();
  const double broadNs = s.cyclesBroad * cyc, totalNs = r.run.stats.modelledNs;
  const auto level = static_cast<std::int32_t>(s.worldCellLevel);
  std::cerr << "collide spheres: " << spheres.size() << " spheres (" << w.badSpheres.size() << " bad), " << w.candidates
            << " candidate pairs, " << w.pairs.size() << " contacts, on the AFU (world mode, cells of edge " << driver::cellEdge(level) << ", "
            << s.worldLarge << " large; " << toString(w.contacts.format) << ", link " << lp.name << " at "
            << lp.clockMHz << " MHz)\n  " << clock.describe() << "\n"
            << std::fixed << std::setprecision(1) << "  modelled time " << totalNs / 1e3 << " us (link bound "
            << r.run.stats.linkBoundNs / 1e3 << " us; " << r.run.stats.readLines << " lines read, " << r.run.stats.writeLines
            << " written; " << afu.lastSlabs() << (afu.lastSlabs() == 1 ? " slab, " : " slabs or boxes, ") << r.attempts
            << (r.attempts == 1 ? " run" : " runs") << " in " << afu.lastCalls()
            << (afu.lastCalls() == 1 ? " call" : " calls") << (afu.driver().options().runQueue ? ", queued" : "") << "): broad phase "
            << broadNs / 1e3 << " us (" << s.cyclesBroad << " cycles; the SCPUs compute during its last pass), the rest "
            << (totalNs - broadNs) / 1e3 << " us (table load, drain, status, call overhead)\n";
  if (w.flaggedMisses)
    std::cerr << "collide spheres: warning: " << w.flaggedMisses
              << " candidate pairs raised overflow or invalid in the AFU's arithmetic and are no contact (world mode "
                 "writes contacts only; `collide pairs --afu` on them gives each one's flags)\n";
  if (summary) {
    nlohmann::json j = {{"spheres", spheres.size()},       {"bad_spheres", w.badSpheres.size()},
                        {"candidates", w.candidates},      {"contacts", w.pairs.size()},
                        {"flagged_misses", w.flaggedMisses},
                        {"backend", "rtl"},                {"broad_phase", "afu"},
                        {"format", toString(w.contacts.format)}, {"repeat", 1},
                        {"broad_ns", broadNs},             {"narrow_ns", totalNs - broadNs},
                        {"finish_ns", 0}};
    j["afu"] = {{"link", lp.name},
                {"clock_mhz", lp.clockMHz},
                {"clock", clock.toJson()},
                {"modelled_ns", totalNs},
                {"link_bound_ns", r.run.stats.linkBoundNs},
                {"runs", r.attempts},
                {"slabs", afu.lastSlabs()},
                {"calls", afu.lastCalls()},
                {"run_queue", afu.driver().options().runQueue},
                {"read_lines", r.run.stats.readLines},
                {"write_lines", r.run.stats.writeLines}};
    j["afu"].update(statusJson(s));
    // Each run's own counts, in the order the AFU ran them (smallest first).
    nlohmann::json perRun = nlohmann::json::array();
    for (const auto& run : afu.lastRuns()) {
      nlohmann::json one = {{"spheres", run.spheres},
                            {"attempts", run.attempts},
                            {"candidates", run.status.pairsProcessed},
                            {"contacts", run.status.contactsFound},
                            {"cycles_wait_read", run.status.cyclesWaitRead},
                            {"cycles_wait_write", run.status.cyclesWaitWrite}};
      one.update(statusJson(run.status));
      perRun.push_back(std::move(one));
    }
    j["afu"]["per_run"] = perRun;
    summary->stream() << j.dump(2) << "\n";
    summary->commit();
  }
  return 0;
}


// The fastest of `repeat` collisions, phase by phase (the least disturbed on a shared
// machine); every run gives the same contacts.
template <typename Collide>
world::WorldTiming fastestOf(int repeat, Collide collideOnce) {
  constexpr auto kMax = std::numeric_limits<std::int64_t>::max();
  world::WorldTiming best{kMax, kMax, kMax};
  for (int k = 0; k < repeat; ++k) {
    world::WorldTiming t;
    collideOnce(t);
    best.broadNs = std::min(best.broadNs, t.broadNs);
    best.narrowNs = std::min(best.narrowNs, t.narrowNs);
    best.finishNs = std::min(best.finishNs, t.finishNs);
  }
  return best;
}

// The tuned grid (world/tuned_world.hpp): simd's contacts, on --threads threads.
int runSpheresGrid(const SpheresOptions& o) {
  if (!o.space.empty()) throw std::invalid_argument("--space " + o.space + " applies to --backend ode, bullet or fcl (grid has its own cells)");
  world::TunedWorld tuned(o.threads.value_or(world::ThreadTeam::hardwareThreads()));
  OutputFile out(o.out, OutputFile::Dash::IsStdout);
  std::unique_ptr<OutputFile> summary = o.summary.empty() ? nullptr : std::make_unique<OutputFile>(o.summary);
  SphereTable spheres;
  readSpheres(o, LinkFormat::Binary32, spheres);
  world::WorldContacts w;
  const world::WorldTiming best = fastestOf(o.repeat, [&](world::WorldTiming& t) { tuned.collide(spheres, w, t); });
  writeWorldContactsCsv(out.stream(), w);
  out.commit();

  std::cerr << "collide spheres: " << spheres.size() << " spheres (" << w.badSpheres.size() << " bad), " << w.candidates
            << " candidate pairs, " << w.pairs.size() << " contacts, " << tuned.name() << ", levels:";
  for (const auto& l : tuned.lastLevels())
    std::cerr << " " << l.spheres << " spheres in cells of " << l.cellEdge << " m (" << l.large << " large);";
  std::cerr << " narrow phase simd (binary32)\n"
            << std::fixed << std::setprecision(1) << "  time (fastest of " << o.repeat << "): broad " << us(best.broadNs)
            << " us, narrow " << us(best.narrowNs) << " us, finish " << us(best.finishNs)
            << " us (broad: cells and the binary32 test; narrow: the contacts' values and flags; finish: ordering)\n";
  if (summary) {
    nlohmann::json levels = nlohmann::json::array();
    for (const auto& l : tuned.lastLevels())
      levels.push_back({{"spheres", l.spheres}, {"large", l.large}, {"cell_edge", l.cellEdge}});
    nlohmann::json j = {{"spheres", spheres.size()},       {"bad_spheres", w.badSpheres.size()},
                        {"candidates", w.candidates},      {"contacts", w.pairs.size()},
                        {"backend", "grid"},               {"broad_phase", "tuned grid"},
                        {"format", toString(w.contacts.format)}, {"repeat", o.repeat},
                        {"threads", tuned.threads()},      {"broad_ns", best.broadNs},
                        {"narrow_ns", best.narrowNs},      {"finish_ns", best.finishNs},
                        {"levels", levels}};
    summary->stream() << j.dump(2) << "\n";
    summary->commit();
  }
  return 0;
}

}  // namespace

int runSpheres(const SpheresOptions& o) {
  return reportErrors("collide spheres", [&]() -> int {
    if (o.threads && (o.backend != "grid" || !o.afu.empty()))
      throw std::invalid_argument("--threads applies to --backend grid (the others run on one thread)");
    if (!o.afu.empty() || o.backend == "rtl") return runSpheresAfu(o);
    refuseClockOption(o.clockMHz, "--backend " + o.backend);
    if (o.backend == "grid") return runSpheresGrid(o);
    Pipeline p = makePipeline(o);
    // Opened first, so that a bad path fails before the work; replaced only when complete.
    OutputFile out(o.out, OutputFile::Dash::IsStdout);
    std::unique_ptr<OutputFile> summary = o.summary.empty() ? nullptr : std::make_unique<OutputFile>(o.summary);
    SphereTable spheres;
    readSpheres(o, p.narrow->format(), spheres);

    world::WorldCollider collider(*p.broad, *p.narrow);
    world::WorldContacts w;
    // Another engine's own narrow phase, on the candidates of each collision (timed apart;
    // its contacts only counted against ours).
    auto* engine = dynamic_cast<world::EngineBroadPhase*>(p.broad.get());
    PairList engineFound;
    std::int64_t engineNs = std::numeric_limits<std::int64_t>::max();
    const world::WorldTiming best = fastestOf(o.repeat, [&](world::WorldTiming& t) {
      collider.collide(spheres, w, t);
      if (!engine) return;
      engineFound = PairList{};
      const auto t0 = std::chrono::steady_clock::now();
      engine->engineContacts(spheres, engineFound);
      engineNs = std::min<std::int64_t>(
          engineNs, std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
    });
    const world::EngineDiff diff = engine ? world::compareContacts(engineFound, w.pairs) : world::EngineDiff{};

    writeWorldContactsCsv(out.stream(), w);
    out.commit();
    const auto* grid = dynamic_cast<const world::GridBroadPhase*>(p.broad.get());
    std::cerr << "collide spheres: " << spheres.size() << " spheres (" << w.badSpheres.size() << " bad), "
              << w.candidates << " candidate pairs, " << w.pairs.size() << " contacts, broad phase " << p.broad->name();
    if (grid)
      std::cerr << " (cells 2^" << grid->lastShape().cellExp << " m, " << grid->lastShape().large << " large, "
                << grid->lastShape().cellPairs << " pairs in neighbouring cells before the box test)";
    std::cerr << ", narrow phase " << p.narrow->name() << " (" << toString(w.contacts.format) << ")\n"
              << std::fixed << std::setprecision(1) << "  time (fastest of " << o.repeat << "): broad " << us(best.broadNs)
              << " us, narrow " << us(best.narrowNs) << " us, finish " << us(best.finishNs)
              << " us (flags, policy, sorting)\n";
    if (engine)
      std::cerr << "  the engine's own narrow phase, " << engine->engineNarrowName() << ", on the same candidates: "
                << us(engineNs) << " us, " << engineFound.size() << " contacts (" << diff.onlyEngine
                << " that binary32 calls no contact, " << diff.onlyExact
                << " binary32 contacts it misses; not written)\n";
    if (summary) {
      nlohmann::json j = {{"spheres", spheres.size()},      {"bad_spheres", w.badSpheres.size()},
                          {"candidates", w.candidates},     {"contacts", w.pairs.size()},
                          {"backend", engine ? o.backend : p.narrow->name()}, {"broad_phase", p.broad->name()},
                          {"format", toString(w.contacts.format)}, {"repeat", o.repeat},
                          {"broad_ns", best.broadNs},       {"narrow_ns", best.narrowNs},
                          {"finish_ns", best.finishNs}};
      if (grid)
        j["grid"] = {{"cell_exp", grid->lastShape().cellExp},
                     {"large", grid->lastShape().large},
                     {"buckets", grid->lastShape().buckets},
                     {"cell_pairs", grid->lastShape().cellPairs}};
      if (engine) {
        j["narrow_phase"] = p.narrow->name();
        j["engine"] = {{"narrow_phase", engine->engineNarrowName()}, {"narrow_ns", engineNs},
                       {"contacts", engineFound.size()},             {"only_engine", diff.onlyEngine},
                       {"only_exact", diff.onlyExact}};
      }
      summary->stream() << j.dump(2) << "\n";
      summary->commit();
    }
    return 0;
  });
}

}  // namespace collide::cli
