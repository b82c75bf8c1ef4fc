#include "link/link_params.hpp"

#include <cmath>
#include <set>
#include <sstream>
#include <tuple>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "util/echo.hpp"

namespace collide::link {

std::vector<ChannelParams> LinkParams::channels() const {
  std::vector<ChannelParams> all;
  all.reserve(1 + moreChannels.size());
  all.push_back(ChannelParams{channelName, readGBps, writeGBps, readLatencyMinNs, readLatencyMaxNs,
                              writeLatencyMinNs, writeLatencyMaxNs});
  all.insert(all.end(), moreChannels.begin(), moreChannels.end());
  return all;
}

void LinkParams::setChannels(const std::vector<ChannelParams>& all) {
  if (all.empty()) throw std::invalid_argument("channels: need at least one");
  const ChannelParams& c = all.front();
  channelName = c.name;
  readGBps = c.readGBps;
  writeGBps = c.writeGBps;
  readLatencyMinNs = c.readLatencyMinNs;
  readLatencyMaxNs = c.readLatencyMaxNs;
  writeLatencyMinNs = c.writeLatencyMinNs;
  writeLatencyMaxNs = c.writeLatencyMaxNs;
  moreChannels.assign(all.begin() + 1, all.end());
}

namespace {
// 0 means unlimited, so one unlimited channel makes the sum unlimited.
double aggregate(const std::vector<ChannelParams>& all, double ChannelParams::*gbps) {
  double sum = 0;
  for (const auto& c : all) {
    if (!(c.*gbps > 0)) return 0.0;
    sum += c.*gbps;
  }
  return sum;
}
}  // namespace

double LinkParams::aggregateReadGBps() const { return aggregate(channels(), &ChannelParams::readGBps); }
double LinkParams::aggregateWriteGBps() const { return aggregate(channels(), &ChannelParams::writeGBps); }

namespace {
std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
std::string rangeText(const ParamRange& r) { return num(r.lo) + ".." + num(r.hi) + " " + r.unit; }
// !(in range) rather than (out of range), so that NaN is refused too.
void inRange(const std::string& key, double v, const ParamRange& r, const char* which = "") {
  if (!(v >= r.lo && v <= r.hi))
    throw std::invalid_argument(key + ": " + which + num(v) + " " + r.unit + " is outside the sane range " +
                                rangeText(r));
}
void bandwidthInRange(const std::string& key, double v) {
  if (v == 0) return;  // unlimited
  if (!(v >= kBandwidthRange.lo && v <= kBandwidthRange.hi))
    throw std::invalid_argument(key + ": " + num(v) + " GB/s is outside the sane range 0 (unlimited) or " +
                                rangeText(kBandwidthRange));
}
}  // namespace

std::uint64_t LinkParams::nsToCycles(double ns) const {
  const double c = std::round(ns / cycleNs());
  // validate() keeps every time below 2^40 cycles; past that the cast would be undefined.
  if (!(c < 0x1p62)) throw std::logic_error("LinkParams::nsToCycles: " + num(ns) + " ns is not a cycle count (unvalidated link)");
  return c < 1.0 ? 1 : static_cast<std::uint64_t>(c);
}

void LinkParams::validate() const {
  auto bad = [](const std::string& what) { throw std::invalid_argument(what); };
  inRange("clock_mhz", clockMHz, kClockRange);
  if (lineBytes != kLineBytes) bad("line_bytes: the AFU contract fixes " + std::to_string(kLineBytes));
  // Channel 0's errors keep the flat key names a scene uses for it.
  const auto all = channels();
  if (all.size() > kMaxChannels)
    bad("channels: " + std::to_string(all.size()) + " channels, at most " + std::to_string(kMaxChannels));
  std::set<std::string> names;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const ChannelParams& c = all[k];
    const std::string at = k == 0 ? "" : "channels[" + std::to_string(k) + "].";
    // Only "channels" sets names, so name errors always give the list index.
    const std::string nameAt = "channels[" + std::to_string(k) + "].name";
    if (c.name.empty()) bad(nameAt + ": must not be empty");
    if (!names.insert(c.name).second) bad(nameAt + ": \"" + c.name + "\" names two channels");
    for (const auto& [key, lo, hi] : {std::tuple{"read_latency_ns", c.readLatencyMinNs, c.readLatencyMaxNs},
                                      std::tuple{"write_latency_ns", c.writeLatencyMinNs, c.writeLatencyMaxNs}}) {
      inRange(at + key, lo, kLatencyRange, lo == hi ? "" : "min ");
      inRange(at + key, hi, kLatencyRange, lo == hi ? "" : "max ");
      if (!(hi >= lo)) bad(at + key + ": need min <= max, got " + num(lo) + " > " + num(hi));
    }
    bandwidthInRange(at + "read_gbps", c.readGBps);
    bandwidthInRange(at + "write_gbps", c.writeGBps);
  }
  for (const auto& [key, n] : {std::pair{"max_reads", maxReads}, std::pair{"max_writes", maxWrites}})
    if (n < 1 || n > kMaxOutstanding)
      bad(std::string(key) + ": " + std::to_string(n) + " is outside the sane range 1.." + std::to_string(kMaxOutstanding));
  inRange("csr_write_ns", csrWriteNs, kCsrPollRange);
  inRange("ready_drop", readyDrop, kReadyDropRange);
  inRange("poll_ns", pollNs, kCsrPollRange);
  inRange("transaction_overhead_ns", transactionOverheadNs, kOverheadRange);
}

namespace {
double number(const nlohmann::json& v, const std::string& path) {
  if (!v.is_number()) throw std::invalid_argument(path + ": expected a number, got " + util::echoJson(v));
  return v.get<double>();
}
void range(const nlohmann::json& v, const std::string& path, double& lo, double& hi) {
  if (v.is_number()) {
    lo = hi = v.get<double>();
  } else if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()) {
    lo = v[0].get<double>();
    hi = v[1].get<double>();
  } else {
    throw std::invalid_argument(path + ": expected a number or [min, max], got " + util::echoJson(v));
  }
  if (!(lo >= 0) || !(hi >= lo))
    throw std::invalid_argument(path + ": expected 0 <= min <= max, got " + util::echoJson(v));
}
double bandwidth(const nlohmann::json& v, const std::string& path) {
  const double g = number(v, path);
  if (!(g >= 0)) throw std::invalid_argument(path + ": expected >= 0 GB/s (0 = unlimited), got " + util::echoJson(v));
  return g;
}
unsigned count(const nlohmann::json& v, const std::string& path) {
  if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > kMaxOutstanding)
    throw std::invalid_argument(path + ": expected an integer in 1.." + std::to_string(kMaxOutstanding) + ", got " +
                                util::echoJson(v));
  return v.get<unsigned>();
}

// The keys that describe one channel, as the flat keys of channel 0 or inside "channels".
bool channelKey(const std::string& key, const nlohmann::json& v, const std::string& at, ChannelParams& c) {
  if (key == "read_latency_ns") range(v, at, c.readLatencyMinNs, c.readLatencyMaxNs);
  else if (key == "write_latency_ns") range(v, at, c.writeLatencyMinNs, c.writeLatencyMaxNs);
  else if (key == "read_gbps") c.readGBps = bandwidth(v, at);
  else if (key == "write_gbps") c.writeGBps = bandwidth(v, at);
  else return false;
  return true;
}

// "channels": [{"name": ..., "read_gbps": ..., "write_gbps": ..., "read_latency_ns": ...,
// "write_latency_ns": ...}, ...], every key required: a channel half inherited from a
// preset would be hard to read.
std::vector<ChannelParams> channelList(const nlohmann::json& v, const std::string& path) {
  if (!v.is_array() || v.empty())
    throw std::invalid_argument(path + ": expected a non-empty array of channels, got " + util::echoJson(v));
  std::vector<ChannelParams> all;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string at = path + "[" + std::to_string(k) + "]";
    const nlohmann::json& e = v[k];
    if (!e.is_object()) throw std::invalid_argument(at + ": expected an object, got " + util::echoJson(e));
    ChannelParams c;
    for (const auto& [key, x] : e.items()) {
      if (key == "name") {
        if (!x.is_string()) throw std::invalid_argument(at + ".name: expected a string, got " + util::echoJson(x));
        c.name = x.get<std::string>();
      } else if (!channelKey(key, x, at + "." + key, c)) {
        throw std::invalid_argument(at + "." + key +
                                    ": unknown key (known here: name, read_gbps, write_gbps, "
                                    "read_latency_ns, write_latency_ns)");
      }
    }
    for (const char* need : {"name", "read_gbps", "write_gbps", "read_latency_ns", "write_latency_ns"})
      if (!e.contains(need)) throw std::invalid_argument(at + "." + need + ": missing");
    all.push_back(c);
  }
  return all;
}
}  // namespace

LinkParams linkParamsFromJson(const nlohmann::json& j, const std::string& path, LinkParams p) {
  if (!j.is_object()) throw std::invalid_argument(path + ": expected an object, got " + util::echoJson(j));
  // "channels" replaces the list; a flat channel key next to it would edit channel 0 of
  // which list? Refuse rather than guess.
  const bool listed = j.contains("channels");
  if (listed) p.setChannels(channelList(j.at("channels"), path + ".channels"));
  ChannelParams first = p.channels().front();
  for (const auto& [key, v] : j.items()) {
    const std::string at = path + "." + key;
    if (key == "type" || key == "channels") continue;  // type: read by the caller (a preset name)
    if (channelKey(key, v, at, first)) {
      if (listed) throw std::invalid_argument(at + ": give it inside \"channels\" when \"channels\" is set");
      continue;
    }
    if (key == "clock_mhz") p.clockMHz = number(v, at);
    else if (key == "max_reads") p.maxReads = count(v, at);
    else if (key == "max_writes") p.maxWrites = count(v, at);
    else if (key == "reorder") {
      if (!v.is_boolean()) throw std::invalid_argument(at + ": expected true or false, got " + util::echoJson(v));
      p.reorder = v.get<bool>();
    } else if (key == "seed") {
      if (!v.is_number_unsigned()) throw std::invalid_argument(at + ": expected an unsigned integer, got " + util::echoJson(v));
      p.seed = v.get<std::uint64_t>();
    } else if (key == "ready_drop") p.readyDrop = number(v, at);
    else if (key == "csr_write_ns") p.csrWriteNs = number(v, at);
    else if (key == "poll_ns") p.pollNs = number(v, at);
    else if (key == "transaction_overhead_ns") p.transactionOverheadNs = number(v, at);
    else throw std::invalid_argument(at + ": unknown key");
  }
  if (!listed) {
    auto all = p.channels();
    all.front() = first;
    p.setChannels(all);
  }
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + "." + e.what());
  }
  return p;
}

}  // namespace collide::link
