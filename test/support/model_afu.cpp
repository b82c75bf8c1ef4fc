#include "support/model_afu.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "collide/simd_kernel.hpp"

namespace collide::test {

using namespace collide::driver;

void ModelAfu::reset() {
  *this = ModelAfu(cfg_);
}

void ModelAfu::start() {
  st_ = StatusLine{};
  sx_.assign(csr_[contract::CSR_NUM_SPHERES], 0); sy_ = sx_; sz_ = sx_; sr_ = sx_;
  compact_.clear();
  denseLines_.clear();
  contactLine_ = 0;
  const bool badBase = !csr_[contract::CSR_SPHERE_BASE] || !csr_[contract::CSR_PAIR_BASE] || !csr_[contract::CSR_CONTACT_BASE] || !csr_[contract::CSR_STATUS_ADDR];
  if (badBase || csr_[contract::CSR_NUM_PAIRS] >= (1u << 24)) {
    st_.errors |= contract::ERR_BAD_CONFIG;
    phase_ = Phase::Finish;
  } else if (csr_[contract::CSR_NUM_SPHERES] > cfg_.maxSpheres) {
    st_.errors |= contract::ERR_TOO_MANY_SPHERES;
    phase_ = Phase::Finish;
  } else {
    phase_ = Phase::Spheres;
    nextLine_ = linesDone_ = 0;
    linesTotal_ = sphereLines(csr_[contract::CSR_NUM_SPHERES], cfg_.format);
  }
}

bool ModelAfu::wantRead() const {
  return (phase_ == Phase::Spheres || phase_ == Phase::Pairs) && nextLine_ < linesTotal_ &&
         rd_.size() < cfg_.maxReads;
}

link::AfuToLink ModelAfu::evalOutputs() {
  out_ = {};
  if (wantRead()) {
    std::uint32_t tag = nextRdTag_;
    while (rd_.count(tag)) tag = (tag + 1) % cfg_.maxReads;
    const std::uint64_t base = phase_ == Phase::Spheres ? csr_[contract::CSR_SPHERE_BASE] : csr_[contract::CSR_PAIR_BASE];
    out_.rdReq = link::ReadReq{base + nextLine_, tag};
  }
  if (wantWrite()) {
    std::uint32_t tag = nextWrTag_;
    while (wrOut_.count(tag)) tag = (tag + 1) % cfg_.maxWrites;
    out_.wrReq = link::WriteReq{wq_.front().first, tag, wq_.front().second};
  }
  return out_;
}

void ModelAfu::clockEdge() {
  ++edges_;
  computedThisCycle_ = false;
  if (in_.csr) {
    const auto& c = *in_.csr;
    if (c.index == contract::CSR_CTRL) {
      if (c.data == 1 && (phase_ == Phase::Idle)) start();
    } else if (c.index < std::size(csr_)) {
      csr_[c.index] = c.data;
    }
  }
  if (in_.rdResp) {
    auto it = rd_.find(in_.rdResp->tag);
    if (it != rd_.end()) {
      const Inflight f = it->second;
      rd_.erase(it);
      onReadData(f, in_.rdResp->data);
    }
  }
  if (in_.wrResp && wrOut_.erase(in_.wrResp->tag)) --wrTagsUsed_;

  bool issued = false;
  if (out_.rdReq && in_.rdReqReady) {
    rd_[out_.rdReq->tag] = Inflight{phase_ == Phase::Spheres, nextLine_++};
    nextRdTag_ = (out_.rdReq->tag + 1) % cfg_.maxReads;
    issued = true;
  }
  if (out_.wrReq && in_.wrReqReady) {
    wq_.pop_front();
    wrOut_[out_.wrReq->tag] = true;
    ++wrTagsUsed_;
    nextWrTag_ = (out_.wrReq->tag + 1) % cfg_.maxWrites;
    issued = true;
  }
  countCycles(issued, 1);
  advance();
}

void ModelAfu::onReadData(const Inflight& f, const link::Line& data) {
  if (f.sphere) {
    const unsigned per = lay_.spheresPerLine();
    for (unsigned s = 0; s < per; ++s) {
      const std::uint64_t k = f.line * per + s;
      if (k >= sx_.size()) break;
      double v[4];
      sphereFromLine(data, s, cfg_.format, v);
      sx_[k] = v[0]; sy_[k] = v[1]; sz_[k] = v[2]; sr_[k] = v[3];
    }
    ++linesDone_;
  } else {
    computePairLine(f.line, data);
    ++linesDone_;
  }
}

namespace {
ContactRecord collideOne(LinkFormat fmt, const double a[4], const double b[4]) {
  ContactRecord r;
  bool hit = false, coincident = false;
  if (fmt == LinkFormat::Binary32) {
    float in[8], res[7];
    std::uint8_t h;
    for (int k = 0; k < 4; ++k) { in[k] = static_cast<float>(a[k]); in[4 + k] = static_cast<float>(b[k]); }
    collideSpheresF32(1, PairsF32{&in[0], &in[1], &in[2], &in[3], &in[4], &in[5], &in[6], &in[7]},
                      ContactsF32{&res[0], &res[1], &res[2], &res[3], &res[4], &res[5], &res[6], &h});
    const float dx = in[0] - in[4], dy = in[1] - in[5], dz = in[2] - in[6];
    coincident = std::sqrt(dx * dx + dy * dy + dz * dz) <= 0.0f;
    hit = h;
    double* o[7] = {&r.px, &r.py, &r.pz, &r.nx, &r.ny, &r.nz, &r.depth};
    for (int k = 0; k < 7; ++k) *o[k] = res[k];
  } else {
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    hit = !(d > a[3] + b[3]);
    coincident = d <= 0;
    if (hit && coincident) {
      r.px = a[0]; r.py = a[1]; r.pz = a[2]; r.nx = 1; r.depth = a[3] + b[3];
    } else if (hit) {
      const double inv = 1.0 / d;
      r.nx = dx * inv; r.ny = dy * inv; r.nz = dz * inv;
      const double k = 0.5 * (b[3] - a[3] - d);
      r.px = a[0] + r.nx * k; r.py = a[1] + r.ny * k; r.pz = a[2] + r.nz * k;
      r.depth = a[3] + b[3] - d;
    }
  }
  r.flags = static_cast<std::uint8_t>((hit ? contract::REC_HIT : 0) |
      ((hit ? (coincident ? contract::KIND_COINCIDENT : contract::KIND_CONTACT) : contract::KIND_SEPARATED) << contract::REC_KIND_SHIFT));
  return r;
}
}  // namespace

void ModelAfu::computePairLine(std::uint64_t line, const link::Line& data) {
  computedThisCycle_ = true;
  const unsigned per = lay_.recordsPerLine();
  for (unsigned slot = 0; slot < contract::PAIRS_PER_LINE; ++slot) {
    const std::uint64_t k = line * contract::PAIRS_PER_LINE + slot;
    if (k >= csr_[contract::CSR_NUM_PAIRS]) break;
    std::uint16_t i, j;
    pairFromLine(data, slot, i, j);
    ++st_.pairsProcessed;
    ContactRecord r;
    if (i >= sx_.size() || j >= sx_.size()) {
      st_.errors |= contract::ERR_INDEX_RANGE;
      st_.firstBadPair = std::min<std::uint32_t>(st_.firstBadPair, static_cast<std::uint32_t>(k));
      r.flags = contract::KIND_INVALID << contract::REC_KIND_SHIFT;
    } else {
      const double a[4] = {sx_[i], sy_[i], sz_[i], sr_[i]}, b[4] = {sx_[j], sy_[j], sz_[j], sr_[j]};
      r = collideOne(cfg_.format, a, b);
      bool finite = true;
      for (int c = 0; c < 4; ++c) finite = finite && std::isfinite(a[c]) && std::isfinite(b[c]);
      if (!finite) {
        ++st_.nonFinitePairs;
        st_.errors |= contract::ERR_NONFINITE;
        r.flags |= contract::REC_NONFINITE;
      }
    }
    r.pair = static_cast<std::uint32_t>(k);
    if (r.hit()) ++st_.contactsFound;
    // A miss with an error flag is a compact record too (as the AFU in pair mode).
    const bool flaggedMiss = r.flaggedMiss();
    if (flaggedMiss) ++st_.flaggedMisses;
    if (csr_[contract::CSR_MODE] & contract::MODE_DENSE) {  // dense: record k is pair k
      if (k >= csr_[contract::CSR_CONTACT_CAPACITY]) { st_.errors |= contract::ERR_CAPACITY; continue; }
      const std::uint64_t cl = lay_.recordLine(k, true);
      link::Line& l = denseLines_[cl];
      contactToLine(l, lay_.recordSlot(k, true), lay_, r);
      ++st_.recordsWritten;
      const bool lineFull = lay_.recordSlot(k, true) == per - 1 || slot == contract::PAIRS_PER_LINE - 1 ||
                            k + 1 == csr_[contract::CSR_NUM_PAIRS];
      if (lineFull) {
        wq_.emplace_back(csr_[contract::CSR_CONTACT_BASE] + cl, l);
        denseLines_.erase(cl);
      }
    } else if (r.hit() || flaggedMiss) {
      queueContact(r);
    }
  }
}

void ModelAfu::queueContact(const ContactRecord& r) {
  if (st_.recordsWritten >= csr_[contract::CSR_CONTACT_CAPACITY]) {
    st_.errors |= contract::ERR_CAPACITY;
    return;
  }
  ++st_.recordsWritten;
  compact_.push_back(r);
  if (compact_.size() == lay_.recordsPerLine()) flushCompact();
}

void ModelAfu::flushCompact() {
  if (compact_.empty()) return;
  link::Line l{};  // a partial line has its unused records zeroed
  for (unsigned s = 0; s < compact_.size(); ++s) contactToLine(l, s, lay_, compact_[s]);
  wq_.emplace_back(csr_[contract::CSR_CONTACT_BASE] + contactLine_++, l);
  compact_.clear();
}

void ModelAfu::advance() {
  for (;;) {
    if (phase_ == Phase::Spheres && nextLine_ == linesTotal_ && rd_.empty()) {
      phase_ = Phase::Pairs;
      nextLine_ = linesDone_ = 0;
      linesTotal_ = pairLines(csr_[contract::CSR_NUM_PAIRS]);
    } else if (phase_ == Phase::Pairs && nextLine_ == linesTotal_ && rd_.empty()) {
      flushCompact();
      phase_ = Phase::Finish;
    } else if (phase_ == Phase::Finish && wq_.empty() && wrTagsUsed_ == 0 && !cfg_.hang) {
      StatusLine s = st_;
      s.done = 1;
      if (cfg_.losePair && s.pairsProcessed) --s.pairsProcessed;
      wq_.emplace_back(csr_[contract::CSR_STATUS_ADDR], encodeStatus(s));
      phase_ = Phase::StatusSent;
    } else if (phase_ == Phase::StatusSent && wq_.empty() && wrTagsUsed_ == 0) {
      phase_ = Phase::Idle;
    } else {
      return;
    }
  }
}

// One classification for stepped and skipped cycles, so skipping is exact.
void ModelAfu::countCycles(bool busy, std::uint64_t n) {
  if (phase_ == Phase::Idle || phase_ == Phase::StatusSent) return;
  st_.cyclesTotal += static_cast<std::uint32_t>(n);
  if (phase_ == Phase::Spheres) st_.cyclesLoading += static_cast<std::uint32_t>(n);
  else if (computedThisCycle_) st_.cyclesComputing += static_cast<std::uint32_t>(n);
  else if (!busy && !rd_.empty()) st_.cyclesWaitRead += static_cast<std::uint32_t>(n);
  else if (!busy && (wrTagsUsed_ || !wq_.empty())) st_.cyclesWaitWrite += static_cast<std::uint32_t>(n);
}

bool ModelAfu::idle() const {
  if (!cfg_.exposeIdle) return false;
  return !wantRead() && !wantWrite();
}

void ModelAfu::skipIdleCycles(std::uint64_t n) {
  computedThisCycle_ = false;
  countCycles(false, n);
}

}  // namespace collide::test
