#include "driver/afu_clock.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "driver/afu_factory.hpp"

namespace collide::driver {

ReachedClock parseReachedClock(const std::string& text, const std::string& family, const std::string& what) {
  try {
    const auto j = nlohmann::json::parse(text);
    const auto& f = j.at("families");
    if (!f.contains(family))
      throw std::runtime_error(what + ": no family " + family + " (has " + f.dump() + ")");
    const auto& r = f.at(family);
    ReachedClock c;
    c.family = family;
    c.block = r.at("slowest_block").get<std::string>();
    c.cellsNs = r.at("cells_ps").get<double>() / 1e3;
    c.proxyMHz = r.at("proxy_mhz").get<double>();
    c.routedMHz = r.at("routed_estimate_mhz").get<double>();
    c.commit = j.value("commit", "");
    if (!(c.cellsNs > 0) || !(c.proxyMHz > 0) || !(c.routedMHz > 0))
      throw std::runtime_error(what + ": family " + family + " has a non-positive delay or clock");
    return c;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(what + ": " + e.what());
  }
}

ClockChoice chooseClock(double targetMHz, const std::optional<ReachedClock>& reached, const std::string& unknownWhy,
                        const std::optional<double>& studyMHz) {
  ClockChoice c;
  c.targetMHz = targetMHz;
  c.reached = reached;
  c.unknownWhy = reached ? "" : unknownWhy;
  c.study = studyMHz.has_value();
  c.usedMHz = studyMHz ? *studyMHz : reached ? std::min(targetMHz, reached->proxyMHz) : targetMHz;
  return c;
}

namespace {
std::string mhz(double f) {
  std::ostringstream o;
  o.precision(f < 100 ? 3 : 4);
  o << f;
  return o.str() + " MHz";
}
}  // namespace

std::string familyName(const std::string& f) {
  return f == "cyclonev" ? "Cyclone V" : f == "arriav" ? "Arria V" : f;
}

std::string ClockChoice::describe() const {
  std::ostringstream o;
  o << "AFU clock " << mhz(usedMHz) << ": ";
  if (study) {
    o << "--clock-mhz, a study";
    if (reached && usedMHz > reached->proxyMHz) o << " above what its cells reach";
    o << "; ";
  } else if (!reached) {
    o << "the target; ";
  } else if (reachesTarget()) {
    o << "the target, reached; ";
  } else {
    o << "what its cells reach, short of the target " << mhz(targetMHz) << "; ";
  }
  if (reached) {
    std::ostringstream ns;
    ns.precision(3);
    ns << reached->cellsNs;
    o << "timing proxy (" << familyName(reached->family) << " cell delays, no routing): slowest block "
      << reached->block << " " << ns.str() << " ns, " << mhz(reached->proxyMHz) << "; about " << mhz(reached->routedMHz)
      << " once routed (a model)";
  } else {
    o << "the clock its Verilog reaches is not known: " << unknownWhy;
  }
  return o.str();
}

nlohmann::json ClockChoice::toJson() const {
  nlohmann::json j = {{"used_mhz", usedMHz}, {"target_mhz", targetMHz}, {"study", study},
                      {"reaches_target", reachesTarget()}};
  if (reached)
    j["reached"] = {{"family", reached->family}, {"slowest_block", reached->block}, {"cells_ns", reached->cellsNs},
                    {"proxy_mhz", reached->proxyMHz}, {"routed_estimate_mhz", reached->routedMHz},
                    {"commit", reached->commit}};
  else
    j["reached"] = nullptr, j["unknown_why"] = unknownWhy;
  return j;
}

std::optional<ReachedClock> builtInReachedClock(std::string& unknownWhy) {
  const std::string text = builtInAfuTiming(unknownWhy);
  if (text.empty()) return std::nullopt;
  return parseReachedClock(text, kClockFamily, "the built-in AFU's timing.json");
}

}  // namespace collide::driver
