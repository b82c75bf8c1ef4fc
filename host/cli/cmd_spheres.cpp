// collide spheres: world mode on the CPU (docs/host.md, "collide spheres").
#include <algorithm>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/output_file.hpp"
#include "cli/spheres_csv.hpp"
#include "collide/backend_factory.hpp"
#include "collide/ode_backend.hpp"
#include "util/input_file.hpp"
#include "world/grid_broad_phase.hpp"
#include "world/ode_space_broad_phase.hpp"
#include "world/world_collider.hpp"

namespace collide::cli {

namespace {

struct Pipeline {
  std::unique_ptr<world::BroadPhase> broad;
  std::unique_ptr<CollisionBackend> narrow;
};

Pipeline makePipeline(const SpheresOptions& o) {
  if (!o.afu.empty() || o.backend == "rtl")
    throw driver::AfuUnavailable("world mode is not built yet: the AFU's on-chip broad phase does not exist (issue 11); "
                      "use --backend simd or --backend ode");
  Pipeline p;
  if (o.backend == "simd") {
    if (!o.space.empty())
      throw std::invalid_argument("--space " + o.space + " applies to --backend ode (simd has its own grid)");
    p.broad = std::make_unique<world::GridBroadPhase>();
  } else if (o.backend == "ode") {
    const std::string space = o.space.empty() ? kDefaultOdeSpace : o.space;
    p.broad = std::make_unique<world::OdeSpaceBroadPhase>(space == "hash" ? world::OdeSpaceKind::Hash
                                                                          : world::OdeSpaceKind::SweepAndPrune);
  } else {
    throw std::invalid_argument("unknown backend '" + o.backend + "' (expected simd or ode)");
  }
  BackendRequest req;  // the construction path of `run` and `pairs` too
  req.name = o.backend;
  p.narrow = makeBackend(req);
  // An ODE space with the ode narrow phase: dCollide on the space's own geoms (narrow is
  // destroyed first, so it never holds them dangling).
  auto* space = dynamic_cast<world::OdeSpaceBroadPhase*>(p.broad.get());
  if (auto* ode = dynamic_cast<OdeBackend*>(p.narrow.get()); ode && space) ode->useGeoms(&space->geoms());
  return p;
}

double us(std::int64_t ns) { return static_cast<double>(ns) / 1e3; }

}  // namespace

int runSpheres(const SpheresOptions& o) {
  return reportErrors("collide spheres", [&]() -> int {
    Pipeline p = makePipeline(o);
    // Opened first, so that a bad path fails before the work; replaced only when complete.
    OutputFile out(o.out, OutputFile::Dash::IsStdout);
    std::unique_ptr<OutputFile> summary = o.summary.empty() ? nullptr : std::make_unique<OutputFile>(o.summary);
    SphereTable spheres;
    if (o.in == "-") {
      readSpheresCsv(std::cin, "<stdin>", p.narrow->format(), spheres);
    } else {
      std::ifstream in = util::openInput(o.in);  // a directory says so
      readSpheresCsv(in, o.in, p.narrow->format(), spheres);
    }

    // The fastest of `repeat` runs, phase by phase (the least disturbed on a shared machine);
    // every run gives the same contacts.
    world::WorldCollider collider(*p.broad, *p.narrow);
    world::WorldContacts w;
    world::WorldTiming best{std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::max(),
                            std::numeric_limits<std::int64_t>::max()};
    for (int k = 0; k < o.repeat; ++k) {
      world::WorldTiming t;
      collider.collide(spheres, w, t);
      best.broadNs = std::min(best.broadNs, t.broadNs);
      best.narrowNs = std::min(best.narrowNs, t.narrowNs);
      best.finishNs = std::min(best.finishNs, t.finishNs);
    }

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
    if (summary) {
      nlohmann::json j = {{"spheres", spheres.size()},      {"bad_spheres", w.badSpheres.size()},
                          {"candidates", w.candidates},     {"contacts", w.pairs.size()},
                          {"backend", p.narrow->name()},    {"broad_phase", p.broad->name()},
                          {"format", toString(w.contacts.format)}, {"repeat", o.repeat},
                          {"broad_ns", best.broadNs},       {"narrow_ns", best.narrowNs},
                          {"finish_ns", best.finishNs}};
      if (grid)
        j["grid"] = {{"cell_exp", grid->lastShape().cellExp},
                     {"large", grid->lastShape().large},
                     {"buckets", grid->lastShape().buckets},
                     {"cell_pairs", grid->lastShape().cellPairs}};
      summary->stream() << j.dump(2) << "\n";
      summary->commit();
    }
    return 0;
  });
}

}  // namespace collide::cli
