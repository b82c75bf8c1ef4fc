#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "afu_contract.hpp"
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

// "3 pairs: 2 non-finite input (8), 1 outside the host's range (32)": each problem flag with
// the number of pairs carrying it (a pair may carry several). Empty when none is set.
std::string flaggedSummary(const std::vector<std::uint8_t>& flags) {
  const struct {
    std::uint32_t bit;
    const char* what;
  } kinds[] = {{contract::REC_NONFINITE, "non-finite input"},
               {contract::REC_ARITH, "arithmetic overflow or invalid"},
               {contract::REC_HOST_RANGE, "outside the host's range or the link format"}};
  const std::uint32_t problems = contract::REC_NONFINITE | contract::REC_ARITH | contract::REC_HOST_RANGE;
  std::size_t any = 0;
  for (auto f : flags) any += (f & problems) != 0;
  if (any == 0) return "";
  std::string s = std::to_string(any) + (any == 1 ? " pair:" : " pairs:");
  const char* sep = " ";
  for (const auto& k : kinds) {
    std::size_t n = 0;
    for (auto f : flags) n += (f & k.bit) != 0;
    if (n == 0) continue;
    s += sep + std::to_string(n) + " " + k.what + " (" + std::to_string(k.bit) + ")";
    sep = ", ";
  }
  return s;
}

int runPairs(const PairsOptions& o) {
  if (o.kind != "sphere-sphere") return runKindPairs(o);
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
    std::vector<std::uint8_t> didNotFit;  // per sphere: a value the backend's format cannot hold
    if (o.in == "-") {
      readPairsCsv(std::cin, "<stdin>", backend->format(), spheres, pairs, didNotFit);
    } else {
      std::ifstream in = util::openInput(o.in);  // a directory says so
      readPairsCsv(in, o.in, backend->format(), spheres, pairs, didNotFit);
    }

    ContactSet contacts;
    collidePairs(*backend, spheres, pairs, contacts, didNotFit);  // flags, one decision on bad pairs

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
    // Last, so that a flagged pair never passes without a word.
    if (const std::string flagged = flaggedSummary(contacts.flags); !flagged.empty())
      std::cerr << "collide pairs: flagged " << flagged << "\n";
    return 0;
  });
}

}  // namespace collide::cli
