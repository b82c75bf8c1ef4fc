#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/clock_option.hpp"
#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/output_file.hpp"
#include "cli/pairs_csv.hpp"
#include "collide/backend_factory.hpp"
#include "collide/input_policy.hpp"
#include "collide/rtl_backend.hpp"
#include "driver/afu_factory.hpp"
#include "link/link_presets.hpp"
#include "util/input_file.hpp"

namespace collide::cli {

int runPairs(const PairsOptions& o) {
  return reportErrors("collide pairs", [&]() -> int {
    BackendRequest req;
    std::optional<driver::ClockChoice> clock;
    if (!o.afu.empty()) {
      req.name = "rtl";
      req.afuDir = o.afu;
      req.link = link::presetParams(o.link);
      clock = applyClockOption(req.link, o.clockMHz);
      req.driver.dense = o.dense;
      req.driver.skipIdle = !o.noSkip;
      req.port.traceFile = o.trace;
      req.port.wallLimitS = o.wallLimit;
    } else {
      req.name = o.backend;
      refuseClockOption(o.clockMHz, "--backend " + o.backend);
      if (!o.trace.empty()) throw std::invalid_argument("--trace needs --afu DIR");
    }
    // The one construction path of `run` and `spheres`' backends too.
    std::unique_ptr<CollisionBackend> backend = makeBackend(req);  // rtl without an AFU: AfuUnavailable

    // Opened first, so that a bad path fails before the work; replaced only when complete.
    OutputFile out(o.out, OutputFile::Dash::IsStdout);
    SphereTable spheres;
    PairList pairs;
    if (o.in == "-") {
      readPairsCsv(std::cin, "<stdin>", backend->format(), spheres, pairs);
    } else {
      std::ifstream in = util::openInput(o.in);  // a directory says so
      readPairsCsv(in, o.in, backend->format(), spheres, pairs);
    }

    ContactSet contacts;
    collidePairs(*backend, spheres, pairs, contacts);  // flags, and one decision on bad pairs

    writeContactsCsv(out.stream(), contacts);
    out.commit();
    std::cerr << "collide pairs: " << pairs.size() << " pairs, " << contacts.hits() << " contacts, backend "
              << backend->name() << " (" << toString(contacts.format) << ")";
    if (auto* rtl = dynamic_cast<RtlBackend*>(backend.get())) {
      const auto& b = rtl->lastBatch();
      std::cerr << ", " << b.runs << " AFU runs, " << b.counters.cyclesTotal << " AFU cycles, "
                << b.stats.modelledNs / 1e3 << " us modelled (link " << req.link.name << " at "
                << req.link.clockMHz << " MHz)\n  " << clock->describe();
    }
    std::cerr << "\n";
    return 0;
  });
}

}  // namespace collide::cli
