#pragma once
// Cycle-level model of the CCI link between host memory and the AFU.
//
// The AFU sees one port (as CCI-P's c0/c1): per direction at most one request accepted and
// one response presented a cycle. Behind it sit one or more physical channels
// (LinkParams::channels(), e.g. HARP v2's QPI and two PCIe links). The link picks the
// channel of each accepted request itself, as CCI-P's eVC_VA ("virtual auto") does: the
// channel whose port frees soonest, ties to the lowest index. Each channel has its own
// latency range and its own bandwidth, i.e. its own port occupancy.
//
// Per cycle: outputs() gives the signals the link drives (ready flags, at most one read
// response, one write response and one CSR write); the AFU answers with its requests;
// tick() is the clock edge: presented responses are consumed (never back-pressured),
// requests with valid && ready are accepted (valid without ready is back-pressure: not
// taken, the AFU keeps it valid), and the cycle advances.
//
// Every piece of state is an absolute cycle time (response due cycles, port-free times),
// so nothing changes between events: nextEventCycle() says when the next response or CSR
// will be presented, and skipTo() may jump there in one step with the same outcome as
// ticking with no requests.
#include <cstdint>
#include <deque>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "link/channels.hpp"
#include "link/host_memory.hpp"
#include "link/link_params.hpp"

namespace collide::link {

// The AFU broke the channel protocol (duplicate outstanding tag, address outside memory).
struct LinkProtocolError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct LinkStats {
  std::uint64_t readsAccepted = 0, writesAccepted = 0;
  std::uint64_t readResponses = 0, writeResponses = 0, csrWrites = 0;
  unsigned maxReadsOutstanding = 0, maxWritesOutstanding = 0;
  std::uint64_t reorderedReadResponses = 0;  // presented before an older outstanding read
  std::uint64_t cyclesSkipped = 0;
  // Requests accepted per channel, in LinkParams::channels() order.
  std::vector<std::uint64_t> readsByChannel, writesByChannel;
};

class LinkModel {
 public:
  static constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

  LinkModel(const LinkParams& params, HostMemory& memory);

  const LinkParams& params() const { return params_; }
  std::uint64_t cycle() const { return cycle_; }
  const LinkStats& stats() const { return stats_; }
  unsigned readsOutstanding() const { return static_cast<unsigned>(reads_.size()); }
  unsigned writesOutstanding() const { return static_cast<unsigned>(writes_.size()); }
  std::size_t channelCount() const { return chans_.size(); }

  LinkToAfu outputs() const;                 // signals for the current cycle
  void tick(const AfuToLink& afu);           // clock edge; throws LinkProtocolError
  void hostWriteCsr(std::uint8_t index, std::uint64_t data);  // posted by the host now

  // Earliest cycle >= cycle() at which outputs().anyEvent() holds; kNever if none is due.
  std::uint64_t nextEventCycle() const;
  // Jump to `target` (cycle() <= target <= nextEventCycle()), as if tick() had been
  // called with no requests on every cycle in between. Throws std::logic_error otherwise.
  void skipTo(std::uint64_t target);

 private:
  struct Pending {
    std::uint64_t due;  // first cycle it may be presented
    std::uint64_t seq;  // acceptance order, for in-order mode and ties
    std::uint32_t tag;
    std::uint64_t addr;
    unsigned channel;
    Line data;  // writes: the data to commit when the response is presented
  };
  // One physical channel's timing: latency range in cycles, line times and port-free
  // times in fixed point (absolute, so nothing moves between events).
  struct Channel {
    std::uint64_t rdLatLo, rdLatHi, wrLatLo, wrLatHi;
    std::uint64_t rdLineFx, wrLineFx;
    // Read bandwidth is spent where the data flows, on the response port; rdBookedFx
    // books it when a read is accepted, so that channel choice sees the reads already
    // sent its way. Writes spend theirs on the request port, which is its own booking.
    std::uint64_t rdBookedFx = 0, rdPortFreeFx = 0, wrPortFreeFx = 0;
  };
  // Fixed point for fractional line times (bandwidth): 2^20 units per cycle.
  static constexpr int kFx = 20;

  static std::uint64_t lineTimeFx(double gbps, double clockMHz);
  static std::uint64_t occupy(std::uint64_t freeFx, std::uint64_t now, std::uint64_t lineFx);
  static std::uint64_t startFx(std::uint64_t freeFx, std::uint64_t now);
  std::uint64_t draw(std::uint64_t lo, std::uint64_t hi);
  // The channel for a request accepted at `now`: earliest start on `port`, lowest index.
  unsigned choose(std::uint64_t Channel::*port, std::uint64_t now) const;
  // When the port that presents p's response is free (reads: its channel's; writes: the
  // one write-response port, a response a cycle).
  std::uint64_t respPortFreeFx(const Pending& p, bool read) const;
  // Index of the entry presented at cycle `now`, or -1.
  int pick(const std::vector<Pending>& q, std::uint64_t now, bool read) const;
  std::uint64_t earliest(const std::vector<Pending>& q, bool read) const;

  LinkParams params_;
  HostMemory& mem_;
  std::mt19937_64 rng_;
  std::uint64_t cycle_ = 0, seq_ = 0;
  std::uint64_t csrLat_;
  std::vector<Channel> chans_;
  std::uint64_t respLineFx_, wrRespPortFreeFx_ = 0;
  std::vector<Pending> reads_, writes_;
  std::deque<std::pair<std::uint64_t, CsrWrite>> csrs_;  // (arrival cycle, write), in order
  LinkStats stats_;
};

}  // namespace collide::link
