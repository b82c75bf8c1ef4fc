#include "link/link_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace collide::link {

LinkModel::LinkModel(const LinkParams& params, HostMemory& memory)
    : params_(params), mem_(memory), rng_(params.seed) {
  params_.validate();
  rdLatLo_ = params_.nsToCycles(params_.readLatencyMinNs);
  rdLatHi_ = std::max(rdLatLo_, params_.nsToCycles(params_.readLatencyMaxNs));
  wrLatLo_ = params_.nsToCycles(params_.writeLatencyMinNs);
  wrLatHi_ = std::max(wrLatLo_, params_.nsToCycles(params_.writeLatencyMaxNs));
  csrLat_ = params_.nsToCycles(params_.csrWriteNs);
  rdLineFx_ = lineTimeFx(params_.readGBps, params_.clockMHz);
  wrLineFx_ = lineTimeFx(params_.writeGBps, params_.clockMHz);
  respLineFx_ = std::uint64_t{1} << kFx;  // one write response per cycle
}

// Cycles (fixed point) a 64-byte line occupies a port at `gbps`; never below one cycle,
// the port width (64 B x 200 MHz = 12.8 GB/s ceiling, ARCHITECTURE.md).
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

// A line leaves the port at cycle `now`; returns when the port is free again. A transfer
// that waited only for the cycle boundary keeps its fractional start (so 1.83 cycles a
// line averages 1.83, not 2); after an idle gap the port restarts at `now` (no burst
// credit beyond that sub-cycle remainder).
std::uint64_t LinkModel::occupy(std::uint64_t freeFx, std::uint64_t now, std::uint64_t lineFx) {
  const std::uint64_t one = std::uint64_t{1} << kFx;
  const std::uint64_t nowFx = now << kFx;
  const std::uint64_t earliest = nowFx >= one ? nowFx - one + 1 : 0;
  return std::max(freeFx, earliest) + lineFx;
}

int LinkModel::pick(const std::vector<Pending>& q, std::uint64_t now, std::uint64_t portFreeFx) const {
  if (q.empty() || (now << kFx) < portFreeFx) return -1;
  int best = -1;
  for (int k = 0; k < static_cast<int>(q.size()); ++k) {
    const Pending& p = q[k];
    if (params_.reorder) {
      // Whichever is due first goes first: the random latencies reorder responses.
      if (p.due <= now && (best < 0 || p.due < q[best].due || (p.due == q[best].due && p.seq < q[best].seq)))
        best = k;
    } else if (best < 0 || p.seq < q[best].seq) {
      best = k;  // in order: only the oldest may go
    }
  }
  if (best >= 0 && q[best].due > now) return -1;
  return best;
}

std::uint64_t LinkModel::earliest(const std::vector<Pending>& q, std::uint64_t portFreeFx) const {
  if (q.empty()) return kNever;
  std::uint64_t due = kNever, oldest = kNever;
  for (const Pending& p : q) {
    if (params_.reorder) due = std::min(due, p.due);
    else if (p.seq < oldest) { oldest = p.seq; due = p.due; }
  }
  const std::uint64_t one = std::uint64_t{1} << kFx;
  const std::uint64_t portFree = (portFreeFx + one - 1) >> kFx;
  return std::max({due, portFree, cycle_});
}

LinkToAfu LinkModel::outputs() const {
  LinkToAfu o;
  o.rdReqReady = reads_.size() < params_.maxReads;
  o.wrReqReady = writes_.size() < params_.maxWrites && (cycle_ << kFx) >= wrPortFreeFx_;
  if (int k = pick(reads_, cycle_, rdPortFreeFx_); k >= 0)
    o.rdResp = ReadResp{reads_[k].tag, mem_.line(reads_[k].addr)};  // data as of delivery
  if (int k = pick(writes_, cycle_, wrRespPortFreeFx_); k >= 0) o.wrResp = WriteResp{writes_[k].tag};
  if (!csrs_.empty() && csrs_.front().first <= cycle_) o.csr = csrs_.front().second;
  return o;
}

void LinkModel::tick(const AfuToLink& afu) {
  const std::uint64_t now = cycle_;
  const LinkToAfu o = outputs();  // what the AFU saw this cycle: the handshake uses it

  // Responses presented this cycle are consumed: the AFU cannot refuse them.
  if (int k = pick(reads_, now, rdPortFreeFx_); k >= 0) {
    for (const Pending& p : reads_)
      if (p.seq < reads_[k].seq) { ++stats_.reorderedReadResponses; break; }
    rdPortFreeFx_ = occupy(rdPortFreeFx_, now, rdLineFx_);
    reads_.erase(reads_.begin() + k);
    ++stats_.readResponses;
  }
  if (int k = pick(writes_, now, wrRespPortFreeFx_); k >= 0) {
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
  if (afu.rdReq && o.rdReqReady) {
    const ReadReq& r = *afu.rdReq;
    if (tagBusy(reads_, r.tag)) fail("read tag " + std::to_string(r.tag) + " already outstanding");
    if (!mem_.contains(r.addr)) fail("read of line " + std::to_string(r.addr) + " outside host memory");
    reads_.push_back(Pending{now + draw(rdLatLo_, rdLatHi_), seq_++, r.tag, r.addr, Line{}});
    ++stats_.readsAccepted;
    stats_.maxReadsOutstanding = std::max<unsigned>(stats_.maxReadsOutstanding, reads_.size());
  }
  if (afu.wrReq && o.wrReqReady) {
    const WriteReq& w = *afu.wrReq;
    if (tagBusy(writes_, w.tag)) fail("write tag " + std::to_string(w.tag) + " already outstanding");
    if (!mem_.contains(w.addr)) fail("write of line " + std::to_string(w.addr) + " outside host memory");
    wrPortFreeFx_ = occupy(wrPortFreeFx_, now, wrLineFx_);
    writes_.push_back(Pending{now + draw(wrLatLo_, wrLatHi_), seq_++, w.tag, w.addr, w.data});
    ++stats_.writesAccepted;
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
  std::uint64_t t = std::min(earliest(reads_, rdPortFreeFx_), earliest(writes_, wrRespPortFreeFx_));
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
