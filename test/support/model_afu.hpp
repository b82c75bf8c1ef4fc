#pragma once
// A behavioural C++ AFU that follows docs/afu-interface.md at cycle level, for testing
// the driver, the link model and cycle skipping before the Verilated AFU exists.
// It is NOT the rtl backend and never stands in for it outside tests.
// Shape (like the paper's design): load the whole sphere table, then stream pair lines;
// each pair line is computed the cycle it arrives (binary32: the simd kernel, so results
// are the fp32 reference); contact lines are written as they fill; the status line last.
#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "batch/batch.hpp"
#include "driver/afu_layout.hpp"
#include "driver/afu_port.hpp"

namespace collide::test {

struct ModelAfuConfig {
  LinkFormat format = LinkFormat::Binary32;
  unsigned maxReads = 64, maxWrites = 64;
  std::uint32_t maxSpheres = 4096;
  bool hang = false;          // never write the status line (watchdog test)
  bool losePair = false;      // report one pair fewer than processed (accounting test)
  bool exposeIdle = true;     // false: idle() is always false (no skipping)
};

class ModelAfu final : public driver::AfuPort {
 public:
  explicit ModelAfu(const ModelAfuConfig& c) : cfg_(c) {}

  void reset() override;
  void setInputs(const link::LinkToAfu& in) override { in_ = in; }
  link::AfuToLink evalOutputs() override;
  void clockEdge() override;
  bool idle() const override;
  void skipIdleCycles(std::uint64_t n) override;

  std::uint64_t edges() const { return edges_; }  // clock edges actually evaluated

 private:
  enum class Phase { Idle, Spheres, Pairs, Finish, StatusSent };
  struct Inflight { bool sphere; std::uint64_t line; };

  void start();
  void onReadData(const Inflight& f, const link::Line& data);
  void computePairLine(std::uint64_t line, const link::Line& data);
  void queueContact(const driver::ContactRecord& r);
  void flushCompact();
  void advance();  // progress that needs no input: next phase, status line
  void countCycles(bool busy, std::uint64_t n);
  bool wantRead() const;
  bool wantWrite() const { return !wq_.empty() && wrTagsUsed_ < cfg_.maxWrites; }

  ModelAfuConfig cfg_;
  driver::BufferLayout lay_{cfg_.format, contract::LAYOUT_FULL};  // full records only
  link::LinkToAfu in_;
  link::AfuToLink out_;
  std::uint64_t csr_[9] = {};
  Phase phase_ = Phase::Idle;
  std::vector<double> sx_, sy_, sz_, sr_;
  std::uint64_t nextLine_ = 0, linesTotal_ = 0, linesDone_ = 0;
  std::map<std::uint32_t, Inflight> rd_;
  std::uint32_t nextRdTag_ = 0, nextWrTag_ = 0;
  unsigned wrTagsUsed_ = 0;
  std::map<std::uint32_t, bool> wrOut_;
  std::deque<std::pair<std::uint64_t, link::Line>> wq_;
  std::vector<driver::ContactRecord> compact_;
  std::uint64_t contactLine_ = 0;
  std::map<std::uint64_t, link::Line> denseLines_;
  bool computedThisCycle_ = false;
  driver::StatusLine st_;
  std::uint64_t edges_ = 0;
};

}  // namespace collide::test
