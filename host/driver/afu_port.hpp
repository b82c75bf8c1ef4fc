#pragma once
// The seam between the host and a cycle-level AFU: the Verilated model (later, in
// verilated_afu_port.cpp) or any C++ model. The driver calls, once per clock cycle:
//
//   port.setInputs(link.outputs());   // drive this cycle's inputs
//   AfuToLink out = port.evalOutputs(); // settle combinational logic, read outputs
//   port.clockEdge();                  // rising edge: registers take the inputs
//   link.tick(out);
//
// valid must not depend on ready within a cycle (CCI rule); the AFU sees ready as an
// input and knows at the edge whether its request was taken (valid && ready).
#include <cstdint>

#include "link/channels.hpp"

namespace collide::driver {

class AfuPort {
 public:
  virtual ~AfuPort() = default;

  // Synchronous reset (a few cycles with reset asserted, then released).
  virtual void reset() = 0;
  virtual void setInputs(const link::LinkToAfu& in) = 0;
  virtual link::AfuToLink evalOutputs() = 0;
  virtual void clockEdge() = 0;

  // Idle-waiting: true when, as long as the link presents no response and no CSR, the
  // AFU will drive no request and change no state except its cycle counters. The
  // Verilated AFU is expected to expose this as an output (`io.idle`) computed from its
  // state: no request pending, every SCPU empty, waiting only on responses or a start.
  // A port that cannot tell returns false and is simply stepped every cycle.
  virtual bool idle() const { return false; }
  // True when idle() can ever hold (the AFU exports an idle or busy port).
  virtual bool reportsIdle() const { return false; }

  // Equivalent to n cycles of {setInputs(no events); evalOutputs(); clockEdge();} while
  // idle() holds: advances the AFU's cycle counters (total, waiting on reads or writes)
  // by n. The default steps n times; a Verilated port overrides it when the AFU has a
  // skip input (e.g. `io.skipCycles`, added to the counters in one edge).
  virtual void skipIdleCycles(std::uint64_t n) {
    link::LinkToAfu quiet;  // nothing presented; ready flags do not matter while idle
    for (std::uint64_t k = 0; k < n; ++k) {
      setInputs(quiet);
      (void)evalOutputs();
      clockEdge();
    }
  }
};

}  // namespace collide::driver
