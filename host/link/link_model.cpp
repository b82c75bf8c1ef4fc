#include "link/link_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace collide::link {

LinkModel::LinkModel(const LinkParams& params, HostMemory& memory)
    : params_(params), mem_(memory), rng_(params.seed) {
  params_.validate();
  for (const ChannelParams& c : params_.channels()) {
    Channel ch{};
    ch.rdLatLo = params_.nsToCycles(c.readLatencyMinNs);
    ch.rdLatHi = std::max(ch.rdLatLo, params_.nsToCycles(c.readLatencyMaxNs));
    ch.wrLatLo = params_.nsToCycles(c.writeLatencyMinNs);
    ch.wrLatHi = std::max(ch.wrLatLo, params_.nsToCycles(c.writeLatencyMaxNs));
    ch.rdLineFx = lineTimeFx(c.readGBps, params_.clockMHz);
    ch.wrLineFx = lineTimeFx(c.writeGBps, params_.clockMHz);
    chans_.push_back(ch);
  }
  csrLat_ = params_.nsToCycles(params_.csrWriteNs);
  respLineFx_ = std::uint64_t{1} << kFx;  // one write response per cycle
  stats_.readsByChannel.assign(chans_.size(), 0);
  stats_.writesByChannel.assign(chans_.size(), 0);
}

// Cycles (fixed point) a 64-byte line occupies a channel's port at `gbps`; never below
// one cycle, the AFU port's width (64 B a cycle: 12.8 GB/s at 200 MHz, 25.6 at 400).
std::uint64_t LinkModel::lineTimeFx(double gbps, double clockMHz) {
  const double one = static_cast<double>(std::uint64_t{1} << kFx);
  if (gbps <= 0) return static_cast<std::uint64_t>(one);
  const double bytesPerCycle = gbps * 1e9 / (clockMHz * 1e6);
  const double cycles = static_cast<double>(kLineBytes) / bytesPerCycle;
  return static_cast<std::uint64_t>(std::ceil(std::max(1.0, cycles) * one));
}

// Uniform in [lo, hi]. Our own mapping (not uniform_int_distribution) so that a seed
// gives the same draws with every standard library; the modulo bias is < 2^-57.
std::uint64_t LinkModel::draw(std::uint64_t lo, std::uint64_t hi) {
  if (hi == lo) return lo;
  return lo + rng_() % (hi - lo + 1);
}

// When a line sent at cycle `now` starts on a port free at `freeFx`. A transfer that
// waited only for the cycle boundary keeps its fractional start (so 1.83 cycles a line
// averages 1.83, not 2); after an idle gap the port restarts at `now` (no burst credit
// beyond that sub-cycle remainder).
std::uint64_t LinkModel::startFx(std::uint64_t freeFx, std::uint64_t now) {
  const std::uint64_t one = std::uint64_t{1} << kFx;
  const std::uint64_t nowFx = now << kFx;
  return std::max(freeFx, nowFx >= one ? nowFx - one + 1 : 0);
}

// A line leaves the port at cycle `now`; returns when the port is free again.
std::uint64_t LinkModel::occupy(std::uint64_t freeFx, std::uint64_t now, std::uint64_t lineFx) {
  return startFx(freeFx, now) + lineFx;
}

// eVC_VA-style: the channel whose port lets this line start first. Comparing start times
// (not raw free times) makes every already-idle channel equal, so ties, and with them
// the choice after a pause, go to the lowest index.
unsigned LinkModel::choose(std::uint64_t Channel::*port, std::uint64_t now) const {
  unsigned best = 0;
  std::uint64_t bestStart = startFx(chans_[0].*port, now);
  for (unsigned k = 1; k < chans_.size(); ++k) {
    const std::uint64_t s = startFx(chans_[k].*port, now);
    if (s < bestStart) { best = k; bestStart = s; }
  }
  return best;
}

std::uint64_t LinkModel::respPortFreeFx(const Pending& p, bool read) const {
  return read ? chans_[p.channel].rdPortFreeFx : wrRespPortFreeFx_;
}

int LinkModel::pick(const std::vector<Pending>& q, std::uint64_t now, bool read) const {
  const std::uint64_t nowFx = now << kFx;
  auto ready = [&](const Pending& p) { return p.due <= now && respPortFreeFx(p, read) <= nowFx; };
  int best = -1;
  for (int k = 0; k < static_cast<int>(q.size()); ++k) {
    const Pending& p = q[k];
    if (params_.reorder) {
      // Whichever is due first (and whose port is free) goes first: the random latencies
      // and the channels reorder responses.
      if (ready(p) && (best < 0 || p.due < q[best].due || (p.due == q[best].due && p.seq < q[best].seq)))
        best = k;
    } else if (best < 0 || p.seq < q[best].seq) {
      best = k;  // in order: only the oldest may go
    }
  }
  if (best >= 0 && !ready(q[best])) return -1;
  return best;
}

// The first cycle >= cycle_ at which pick() finds an entry: nothing changes between
// events, so an entry is ready from max(due, its port's free cycle) on.
std::uint64_t LinkModel::earliest(const std::vector<Pending>& q, bool read) const {
  const std::uint64_t one = std::uint64_t{1} << kFx;
  auto readyAt = [&](const Pending& p) {
    return std::max(p.due, (respPortFreeFx(p, read) + one - 1) >> kFx);
  };
  std::uint64_t t = kNever;
  const Pending* oldest = nullptr;
  for (const Pending& p : q) {
    if (params_.reorder) t = std::min(t, readyAt(p));
    else if (!oldest || p.seq < oldest->seq) oldest = &p;
  }
  if (oldest) t = readyAt(*oldest);
  return t == kNever ? kNever : std::max(t, cycle_);
}

namespace {
// A uniform draw in [0, 1) from (seed, cycle, port) alone (splitmix64), so outputs() stays a
// pure function of the state and a skipped stretch needs no draws.
double dropDraw(std::uint64_t seed, std::uint64_t cycle, unsigned port) {
  std::uint64_t z = seed ^ (cycle * 2 + port) * 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}
}  // namespace

LinkToAfu LinkModel::outputs() const {
  LinkToAfu o;
  const std::uint64_t nowFx = cycle_ << kFx;
  const bool dropRd = params_.readyDrop > 0 && dropDraw(params_.seed, cycle_, 0) < params_.readyDrop;
  const bool dropWr = params_.readyDrop > 0 && dropDraw(params_.seed, cycle_, 1) < params_.readyDrop;
  o.rdReqReady = !dropRd && reads_.size() < params_.maxReads;
  o.wrReqReady = !dropWr && writes_.size() < params_.maxWrites &&
                 std::any_of(chans_.begin(), chans_.end(), [&](const Channel& c) { return c.wrPortFreeFx <= nowFx; });
  if (int k = pick(reads_, cycle_, true); k >= 0)
    o.rdResp = ReadResp{reads_[k].tag, mem_.line(reads_[k].addr)};  // data as of delivery
  if (int k = pick(writes_, cycle_, false); k >= 0) o.wrResp = WriteResp{writes_[k].tag};
  if (!csrs_.empty() && csrs_.front().first <= cycle_) o.csr = csrs_.front().second;
  return o;
}

void LinkModel::tick(const AfuToLink& afu) {
  const std::uint64_t now = cycle_;
  const LinkToAfu o = outputs();  // what the AFU saw this cycle: the handshake uses it

  // Responses presented this cycle are consumed: the AFU cannot refuse them.
  if (int k = pick(reads_, now, true); k >= 0) {
    for (const Pending& p : reads_)
      if (p.seq < reads_[k].seq) { ++stats_.reorderedReadResponses; break; }
    Channel& c = chans_[reads_[k].channel];
    c.rdPortFreeFx = occupy(c.rdPortFreeFx, now, c.rdLineFx);
    reads_.erase(reads_.begin() + k);
    ++stats_.readResponses;
  }
  if (int k = pick(writes_, now, false); k >= 0) {
    mem_.line(writes_[k].addr) = writes_[k].data;  // visible to the host when acknowledged
    wrRespPortFreeFx_ = occupy(wrRespPortFreeFx_, now, respLineFx_);
    writes_.erase(writes_.begin() + k);
    ++stats_.writeResponses;
  }
  if (o.csr) {
    csrs_.pop_front();
    ++stats_.csrWrites;
  }

  auto tagBusy = [](const std::vector<Pending>& q, std::uint32_t tag) {
    return std::any_of(q.begin(), q.end(), [&](const Pending& p) { return p.tag == tag; });
  };
  auto fail = [now](const std::string& what) {
    throw LinkProtocolError("link cycle " + std::to_string(now) + ": " + what);
  };
  // valid && !ready is back-pressure, not an error: the request is simply not taken.
  // One RNG draw per accepted request, reads before writes: a seed replays exactly.
  if (afu.rdReq && o.rdReqReady) {
    const ReadReq& r = *afu.rdReq;
    if (tagBusy(reads_, r.tag)) fail("read tag " + std::to_string(r.tag) + " already outstanding");
    if (!mem_.contains(r.addr)) fail("read of line " + std::to_string(r.addr) + " outside host memory");
    const unsigned ch = choose(&Channel::rdBookedFx, now);
    Channel& c = chans_[ch];
    c.rdBookedFx = occupy(c.rdBookedFx, now, c.rdLineFx);
    reads_.push_back(Pending{now + draw(c.rdLatLo, c.rdLatHi), seq_++, r.tag, r.addr, ch, Line{}});
    ++stats_.readsAccepted;
    ++stats_.readsByChannel[ch];
    stats_.maxReadsOutstanding = std::max<unsigned>(stats_.maxReadsOutstanding, reads_.size());
  }
  if (afu.wrReq && o.wrReqReady) {
    const WriteReq& w = *afu.wrReq;
    if (tagBusy(writes_, w.tag)) fail("write tag " + std::to_string(w.tag) + " already outstanding");
    if (!mem_.contains(w.addr)) fail("write of line " + std::to_string(w.addr) + " outside host memory");
    // wrReqReady promised a free write port; the earliest start is on a free one.
    const unsigned ch = choose(&Channel::wrPortFreeFx, now);
    Channel& c = chans_[ch];
    c.wrPortFreeFx = occupy(c.wrPortFreeFx, now, c.wrLineFx);
    writes_.push_back(Pending{now + draw(c.wrLatLo, c.wrLatHi), seq_++, w.tag, w.addr, ch, w.data});
    ++stats_.writesAccepted;
    ++stats_.writesByChannel[ch];
    stats_.maxWritesOutstanding = std::max<unsigned>(stats_.maxWritesOutstanding, writes_.size());
  }
  ++cycle_;
}

void LinkModel::hostWriteCsr(std::uint8_t index, std::uint64_t data) {
  // Posted MMIO writes arrive in order, at most one per cycle.
  std::uint64_t at = cycle_ + csrLat_;
  if (!csrs_.empty()) at = std::max(at, csrs_.back().first + 1);
  csrs_.emplace_back(at, CsrWrite{index, data});
}

std::uint64_t LinkModel::nextEventCycle() const {
  std::uint64_t t = std::min(earliest(reads_, true), earliest(writes_, false));
  if (!csrs_.empty()) t = std::min(t, std::max(csrs_.front().first, cycle_));
  return t;
}

void LinkModel::skipTo(std::uint64_t target) {
  if (target < cycle_ || target > nextEventCycle())
    throw std::logic_error("LinkModel::skipTo(" + std::to_string(target) + ") from cycle " +
                           std::to_string(cycle_) + " past the next event at " +
                           std::to_string(nextEventCycle()));
  stats_.cyclesSkipped += target - cycle_;
  cycle_ = target;
}

}  // namespace collide::link
