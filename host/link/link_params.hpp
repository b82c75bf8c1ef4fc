#pragma once
// Parameters of the host<->AFU link model. Defaults are HARP v1 (Xeon E5-2680 v2 +
// Stratix V over QPI/CCI); each names its source. Treat them as calibratable.
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace collide::link {

struct LinkParams {
  std::string name = "qpi";
  // ARCHITECTURE.md "AFU/CCI clock 200 MHz".
  double clockMHz = 200.0;
  // ARCHITECTURE.md "Data moves in 64-byte lines". Fixed by the AFU contract.
  unsigned lineBytes = 64;
  // NOTES.md / ARCHITECTURE.md: one in-flight read about 200-290 ns round trip
  // (HARP v1 microbenchmark logs). Drawn uniformly per request, in whole cycles.
  double readLatencyMinNs = 200.0, readLatencyMaxNs = 290.0;
  // No HARP v1 figure for the write-response latency in our notes: assumed equal to the
  // read round trip. Calibrate when a measurement exists.
  double writeLatencyMinNs = 200.0, writeLatencyMaxNs = 290.0;
  // ARCHITECTURE.md: about 7 GB/s read, 5 GB/s write sustained (Choi et al., DAC 2016).
  // 0 = unlimited (only the port's one line per cycle = 12.8 GB/s at 200 MHz).
  double readGBps = 7.0, writeGBps = 5.0;
  // ARCHITECTURE.md / NOTES.md: SPL's 6-bit tags, 64 reads and 64 writes outstanding.
  unsigned maxReads = 64, maxWrites = 64;
  // NOTES.md: responses may return out of order. Off: responses in request order.
  bool reorder = true;
  std::uint64_t seed = 1;  // the latency/reordering RNG
  // Host MMIO CSR write, issue to arrival at the AFU. No measured figure in our notes:
  // assumed about one QPI traversal, half the 200-290 ns round trip.
  double csrWriteNs = 125.0;
  // Cost of one status-line poll by the CPU: the AFU's write invalidated the line, so a
  // poll that sees it pays a QPI round trip (NOTES.md 200-290 ns; upper end taken).
  double pollNs = 290.0;
  // Fixed host cost per AFU call (AAL transaction configuration and handshake):
  // the paper says about 5 us; the measured HARP v1 start+poll cost was about 8.5 us
  // (NOTES.md). Added to the modelled time of each run, outside the cycle model.
  double transactionOverheadNs = 5000.0;

  static LinkParams qpi();
  // Preloaded/ideal link: 1-cycle latency both ways, no bandwidth limit beyond one line
  // per cycle per port, no reordering, free CSRs, polls and transactions.
  static LinkParams ideal();

  double cycleNs() const { return 1000.0 / clockMHz; }
  std::uint64_t nsToCycles(double ns) const;  // rounded to nearest, at least 1
  // Throws std::invalid_argument naming the bad field.
  void validate() const;
};

// Reads overrides from a JSON object over `base` (keys as in docs/host.md); throws
// std::invalid_argument with the key path on a bad value or an unknown key.
LinkParams linkParamsFromJson(const nlohmann::json& j, const std::string& path, LinkParams base);

}  // namespace collide::link
