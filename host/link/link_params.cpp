#include "link/link_params.hpp"

#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace collide::link {

LinkParams LinkParams::qpi() { return LinkParams{}; }

LinkParams LinkParams::ideal() {
  LinkParams p;
  p.name = "ideal";
  p.readLatencyMinNs = p.readLatencyMaxNs = p.cycleNs();
  p.writeLatencyMinNs = p.writeLatencyMaxNs = p.cycleNs();
  p.readGBps = p.writeGBps = 0.0;
  p.reorder = false;
  p.csrWriteNs = p.cycleNs();
  p.pollNs = 0.0;
  p.transactionOverheadNs = 0.0;
  return p;
}

std::uint64_t LinkParams::nsToCycles(double ns) const {
  const double c = std::round(ns / cycleNs());
  return c < 1.0 ? 1 : static_cast<std::uint64_t>(c);
}

void LinkParams::validate() const {
  auto bad = [](const char* what) { throw std::invalid_argument(what); };
  if (!(clockMHz > 0)) bad("clock_mhz: must be > 0");
  if (lineBytes != 64) bad("line_bytes: the AFU contract fixes 64");
  if (!(readLatencyMinNs >= 0) || !(readLatencyMaxNs >= readLatencyMinNs))
    bad("read_latency_ns: need 0 <= min <= max");
  if (!(writeLatencyMinNs >= 0) || !(writeLatencyMaxNs >= writeLatencyMinNs))
    bad("write_latency_ns: need 0 <= min <= max");
  if (!(readGBps >= 0) || !(writeGBps >= 0)) bad("read_gbps/write_gbps: must be >= 0 (0 = unlimited)");
  if (maxReads == 0 || maxWrites == 0) bad("max_reads/max_writes: must be >= 1");
  if (!(csrWriteNs >= 0) || !(pollNs >= 0) || !(transactionOverheadNs >= 0))
    bad("csr_write_ns/poll_ns/transaction_overhead_ns: must be >= 0");
}

namespace {
double number(const nlohmann::json& v, const std::string& path) {
  if (!v.is_number()) throw std::invalid_argument(path + ": expected a number, got " + v.dump());
  return v.get<double>();
}
void range(const nlohmann::json& v, const std::string& path, double& lo, double& hi) {
  if (v.is_number()) {
    lo = hi = v.get<double>();
  } else if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()) {
    lo = v[0].get<double>();
    hi = v[1].get<double>();
  } else {
    throw std::invalid_argument(path + ": expected a number or [min, max], got " + v.dump());
  }
  if (!(lo >= 0) || !(hi >= lo))
    throw std::invalid_argument(path + ": expected 0 <= min <= max, got " + v.dump());
}
unsigned count(const nlohmann::json& v, const std::string& path) {
  if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > 1 << 20)
    throw std::invalid_argument(path + ": expected a positive integer, got " + v.dump());
  return v.get<unsigned>();
}
}  // namespace

LinkParams linkParamsFromJson(const nlohmann::json& j, const std::string& path, LinkParams p) {
  if (!j.is_object()) throw std::invalid_argument(path + ": expected an object, got " + j.dump());
  for (const auto& [key, v] : j.items()) {
    const std::string at = path + "." + key;
    if (key == "type") continue;  // read by the caller (qpi | ideal)
    else if (key == "clock_mhz") p.clockMHz = number(v, at);
    else if (key == "read_latency_ns") range(v, at, p.readLatencyMinNs, p.readLatencyMaxNs);
    else if (key == "write_latency_ns") range(v, at, p.writeLatencyMinNs, p.writeLatencyMaxNs);
    else if (key == "read_gbps") p.readGBps = number(v, at);
    else if (key == "write_gbps") p.writeGBps = number(v, at);
    else if (key == "max_reads") p.maxReads = count(v, at);
    else if (key == "max_writes") p.maxWrites = count(v, at);
    else if (key == "reorder") {
      if (!v.is_boolean()) throw std::invalid_argument(at + ": expected true or false, got " + v.dump());
      p.reorder = v.get<bool>();
    } else if (key == "seed") {
      if (!v.is_number_unsigned()) throw std::invalid_argument(at + ": expected an unsigned integer, got " + v.dump());
      p.seed = v.get<std::uint64_t>();
    } else if (key == "csr_write_ns") p.csrWriteNs = number(v, at);
    else if (key == "poll_ns") p.pollNs = number(v, at);
    else if (key == "transaction_overhead_ns") p.transactionOverheadNs = number(v, at);
    else throw std::invalid_argument(at + ": unknown key");
  }
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + "." + e.what());
  }
  return p;
}

}  // namespace collide::link
