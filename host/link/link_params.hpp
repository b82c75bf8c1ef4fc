#pragma once
// Parameters of the host<->AFU link model. The defaults are HARP v1 (Xeon E5-2680 v2 +
// Stratix V over QPI/CCI), each naming its source; link/link_presets.cpp holds the other
// platforms. Treat every number as calibratable.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "link/host_memory.hpp"

namespace collide::link {

// The AFU clock when nothing sets one: the one place for it (LinkParams and the AFU port's
// trace axis start here; a link preset or scene may change it). Stratix V AFU clock 200 MHz
// (Alves et al., "Designing a Collision Detection Accelerator on a Heterogeneous CPU-FPGA
// Platform", Table II): the CCI interface clock. The manifest's clockMHz is the generator's
// nominal figure, which the host does not read: the link decides the simulated clock.
inline constexpr double kDefaultClockMHz = 200.0;

// The sane range of every number, checked by LinkParams::validate() before anything is
// converted to cycles or to the model's fixed point (docs/host.md, "Link parameter
// ranges"). Wide enough for any platform we know of, narrow enough that no conversion can
// overflow: 1 ms at 2 GHz is 2e9 cycles, a line at 0.001 GB/s 1.3e8 cycles (2^20 fixed
// point: 1.3e14, far below 2^64).
struct ParamRange {
  double lo, hi;
  const char* unit;
};
inline constexpr ParamRange kClockRange{1, 2000, "MHz"};         // FPGA interface clocks: 100-800
inline constexpr ParamRange kLatencyRange{0, 1e6, "ns"};         // a trip: up to 1 ms
inline constexpr ParamRange kBandwidthRange{0.001, 10000, "GB/s"};  // or 0 = unlimited
inline constexpr ParamRange kCsrPollRange{0, 1e6, "ns"};         // csr_write_ns, poll_ns
inline constexpr ParamRange kOverheadRange{0, 1e9, "ns"};        // a call's overhead: up to 1 s
inline constexpr ParamRange kReadyDropRange{0, 0.9, ""};          // a fraction of cycles
inline constexpr unsigned kMaxOutstanding = 1u << 20;            // max_reads, max_writes
inline constexpr std::size_t kMaxChannels = 16;

// One physical link between host memory and the FPGA (HARP v2 has a QPI link and two PCIe
// links behind one CCI-P port). Bandwidth 0 = unlimited: only the AFU port's line a cycle.
struct ChannelParams {
  std::string name;
  double readGBps = 0, writeGBps = 0;
  double readLatencyMinNs = 0, readLatencyMaxNs = 0;
  double writeLatencyMinNs = 0, writeLatencyMaxNs = 0;
};

struct LinkParams {
  std::string name = "qpi";
  double clockMHz = kDefaultClockMHz;  // HARP v1's, above
  // CCI moves 64-byte cache lines. Fixed by the AFU contract (kLineBytes).
  unsigned lineBytes = kLineBytes;

  // ---- Channel 0, the only one unless moreChannels is set. These flat fields stay the
  // first channel so that every scene and test written before channels existed means the
  // same thing.
  std::string channelName = "QPI";
  // One in-flight read about 200-290 ns round trip (public HARP v1 microbenchmark logs).
  // Drawn uniformly per request, in whole cycles.
  double readLatencyMinNs = 200.0, readLatencyMaxNs = 290.0;
  // No published HARP v1 write-response latency: assumed equal to the read round trip.
  double writeLatencyMinNs = 200.0, writeLatencyMaxNs = 290.0;
  // About 7 GB/s read, 5 GB/s write sustained on HARP v1 (Choi et al., "A Quantitative
  // Analysis on Microarchitectures of Modern CPU-FPGA Platforms", DAC 2016).
  // 0 = unlimited (only the port's one line per cycle = 12.8 GB/s at 200 MHz).
  double readGBps = 7.0, writeGBps = 5.0;
  // Channels 1.. (their names must differ from channelName and from each other).
  std::vector<ChannelParams> moreChannels;

  // ---- The AFU port, shared by every channel.
  // SPL2's 6-bit request tags on HARP v1: 64 reads and 64 writes outstanding.
  unsigned maxReads = 64, maxWrites = 64;
  // CCI may return responses out of order. Off: responses in request order.
  bool reorder = true;
  std::uint64_t seed = 1;  // the latency/reordering RNG
  // Test only (no platform has it): the fraction of cycles in which the link drops a request
  // port's ready at random (each port, each cycle, drawn from seed and cycle), to test that
  // the AFU survives back-pressure. 0 on every preset.
  double readyDrop = 0.0;
  // Host MMIO CSR write, issue to arrival at the AFU. No published figure: assumed about
  // one QPI traversal, half the 200-290 ns round trip.
  double csrWriteNs = 125.0;
  // Cost of one status-line poll by the CPU: the AFU's write invalidated the line, so a
  // poll that sees it pays a QPI round trip (200-290 ns, upper end taken).
  double pollNs = 290.0;
  // Fixed host cost per AFU call (AAL transaction configuration and handshake): about 5 us
  // in Alves et al. (Section V); start+poll measured about 8.5 us in public HARP v1
  // microbenchmark logs. Added to the modelled time of each run, outside the cycle model.
  double transactionOverheadNs = 5000.0;

  // Presets (numbers and sources in link/link_presets.cpp; link::presets() lists them).
  static LinkParams qpi();    // HARP v1 (also "harp1")
  // Preloaded/ideal link: 1-cycle latency both ways, no bandwidth limit beyond one line
  // per cycle per port, no reordering, free CSRs, polls and transactions.
  static LinkParams ideal();
  static LinkParams harp2();  // HARP v2: QPI + 2 x PCIe Gen3 x8 in one package
  static LinkParams pac();    // Intel PAC with Arria 10 GX: one PCIe Gen3 x8
  static LinkParams cxl();    // a CXL-class link on PCIe 5.0 x16

  // Every channel, channel 0 (the flat fields) first.
  std::vector<ChannelParams> channels() const;
  // Replaces every channel: the first goes to the flat fields. Throws on an empty list.
  void setChannels(const std::vector<ChannelParams>& all);
  // Sum over the channels; 0 (unlimited) if any channel is unlimited.
  double aggregateReadGBps() const;
  double aggregateWriteGBps() const;
  // One line per cycle: what the AFU port carries a direction at most.
  double portGBps() const { return lineBytes * clockMHz / 1000.0; }

  double cycleNs() const { return 1000.0 / clockMHz; }
  std::uint64_t nsToCycles(double ns) const;  // rounded to nearest, at least 1
  // Throws std::invalid_argument naming the bad field, its value and its range.
  void validate() const;
};

// Reads overrides from a JSON object over `base` (keys as in docs/host.md); throws
// std::invalid_argument with the key path on a bad value or an unknown key. The flat
// per-channel keys set channel 0; "channels" replaces every channel.
LinkParams linkParamsFromJson(const nlohmann::json& j, const std::string& path, LinkParams base);

}  // namespace collide::link
