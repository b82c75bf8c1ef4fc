#include <iostream>
#include <sstream>

#include "cli/commands.hpp"
#include "driver/afu_factory.hpp"
#include "driver/manifest.hpp"
#include "link/link_presets.hpp"

namespace collide::cli {

namespace {

std::string num(double v) {  // shortest plain form: 6.23, 20.46, 5000
  std::ostringstream s;
  s << v;
  return s.str();
}
std::string gbps(double v) { return v > 0 ? num(v) + " GB/s" : "unlimited"; }
std::string nsRange(double lo, double hi) { return lo == hi ? num(lo) + " ns" : num(lo) + "-" + num(hi) + " ns"; }

void printPreset(std::ostream& os, const link::LinkPreset& p) {
  const link::LinkParams& lp = p.params;
  os << p.name;
  for (const auto& a : p.aliases) os << " (also " << a << ")";
  os << ": " << p.description << "\n";
  os << "  clock " << num(lp.clockMHz) << " MHz (AFU port " << num(lp.portGBps()) << " GB/s a direction), "
     << lp.maxReads << " reads / " << lp.maxWrites << " writes outstanding, responses "
     << (lp.reorder ? "out of order" : "in order") << "\n";
  const auto chans = lp.channels();
  for (const auto& c : chans)
    os << "  channel " << c.name << ": read " << gbps(c.readGBps) << ", write " << gbps(c.writeGBps)
       << "; read latency " << nsRange(c.readLatencyMinNs, c.readLatencyMaxNs) << ", write latency "
       << nsRange(c.writeLatencyMinNs, c.writeLatencyMaxNs) << "\n";
  if (chans.size() > 1)
    os << "  together: read " << gbps(lp.aggregateReadGBps()) << ", write " << gbps(lp.aggregateWriteGBps())
       << " (requests go to the channel whose port frees first)\n";
  os << "  per call: transaction overhead " << num(lp.transactionOverheadNs) << " ns, CSR write "
     << num(lp.csrWriteNs) << " ns, poll " << num(lp.pollNs) << " ns\n";
  os << "  sources:\n";
  for (const auto& s : p.sources) os << "    - " << s << "\n";
}

}  // namespace

int runInfo(const InfoOptions& o) {
  try {
    if (o.links) {
      std::cout << "link presets (collide run/pairs --link NAME, or a scene's \"link\": {\"type\": NAME}):\n";
      for (const auto& p : link::presets()) {
        std::cout << "\n";
        printPreset(std::cout, p);
      }
      return 0;
    }
    const auto m = driver::loadManifest(o.afu);
    std::cout << m.raw.dump(2) << "\n";
    const auto preset = driver::builtInAfuPreset();
    std::cerr << "host: link format " << toString(m.format) << ", max spheres " << m.maxSpheres
              << "; Verilated AFU in this build: " << (preset.empty() ? "none" : preset) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "collide info: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace collide::cli
