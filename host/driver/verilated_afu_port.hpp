#pragma once
// AfuPort over a Verilated AFU top (Verilator 5: VerilatedContext + model, no globals).
//
// Header-only template so that the generated AFU (driver/verilated_afu_port.cpp) and the
// test double (test/support/afu_test_double) share one harness. Include it only from a
// target that was Verilated (it needs verilated.h and the VM_TRACE* definitions that
// verilate() sets on that target).
//
// Port names are Chisel's flattening of the top's `io = IO(new LinkIO(...))` (docs/afu.md,
// docs/afu-interface.md):
//   clock, reset,
//   io_rdReq_{valid,ready,bits_addr,bits_tag}, io_rdResp_{valid,bits_tag,bits_data},
//   io_wrReq_{valid,ready,bits_addr,bits_tag,bits_data}, io_wrResp_{valid,bits_tag},
//   io_csr_{valid,bits_index,bits_data}
// and, optional, found at compile time, each as io_<name> or <name>:
//   io_idle        (out) high exactly when, without a response or CSR, the AFU drives no
//                  request and changes no state but its cycle counters; must be a
//                  function of registers only (it is read after the clock edge).
//   io_skipCycles  (in, with io_idle) an edge with io_skipCycles = n > 0, given only while
//                  io_idle, counts as n idle cycles (the counters add n at once).
//   io_busy        (out) a run is in progress. Without io_idle, idle() = !io_busy: exact,
//                  but only the waits between runs are skipped then.
// 512-bit lines are VlWide<16>: 32-bit word k holds line bytes 4k..4k+3, little-endian
// (line byte b at bits 8b+7..8b, as LinkIO.scala documents).
//
// Timing: one clock cycle = 1e3/clockMHz ns of simulated time; inputs and outputs of cycle
// c are dumped at c*period, the rising edge at c*period + period/2. Skipped cycles appear
// in a trace as a jump of time.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include <verilated.h>
#if VM_TRACE_FST
#include <verilated_fst_c.h>
#endif
#if VM_TRACE_VCD
#include <verilated_vcd_c.h>
#endif

#include "driver/afu_factory.hpp"
#include "driver/afu_port.hpp"

namespace collide::driver {

namespace vport {

// Optional ports, as `io_x` (inside the io bundle) or `x` (a top-level IO of its own).
#define COLLIDE_VPORT_DETECT(Name, port)                                                              \
  template <class T, class = void> struct Has##Name##Io : std::false_type {};                       \
  template <class T> struct Has##Name##Io<T, std::void_t<decltype(std::declval<T&>().io_##port)>>  \
      : std::true_type {};                                                                          \
  template <class T, class = void> struct Has##Name##Top : std::false_type {};                      \
  template <class T> struct Has##Name##Top<T, std::void_t<decltype(std::declval<T&>().port)>>      \
      : std::true_type {};                                                                          \
  template <class T> auto& port##Of(T& t) {                                                         \
    if constexpr (Has##Name##Io<T>::value) return t.io_##port;                                      \
    else return t.port;                                                                             \
  }                                                                                                 \
  template <class T> constexpr bool has##Name = Has##Name##Io<T>::value || Has##Name##Top<T>::value;
COLLIDE_VPORT_DETECT(Idle, idle)
COLLIDE_VPORT_DETECT(Skip, skipCycles)
COLLIDE_VPORT_DETECT(Busy, busy)
#undef COLLIDE_VPORT_DETECT

// Which trace formats the model was Verilated with (--trace / --trace-fst).
#if VM_TRACE_FST
template <class T, class = void> struct CanFst : std::false_type {};
template <class T>
struct CanFst<T, std::void_t<decltype(std::declval<T&>().trace(static_cast<VerilatedFstC*>(nullptr), 0))>>
    : std::true_type {};
#else
template <class T> struct CanFst : std::false_type {};
#endif
#if VM_TRACE_VCD
template <class T, class = void> struct CanVcd : std::false_type {};
template <class T>
struct CanVcd<T, std::void_t<decltype(std::declval<T&>().trace(static_cast<VerilatedVcdC*>(nullptr), 0))>>
    : std::true_type {};
#else
template <class T> struct CanVcd : std::false_type {};
#endif

template <class W>
void lineToWide(const link::Line& l, W& w) {
  for (int k = 0; k < 16; ++k)
    w[k] = static_cast<std::uint32_t>(l[4 * k]) | static_cast<std::uint32_t>(l[4 * k + 1]) << 8 |
           static_cast<std::uint32_t>(l[4 * k + 2]) << 16 | static_cast<std::uint32_t>(l[4 * k + 3]) << 24;
}

template <class W>
link::Line wideToLine(const W& w) {
  link::Line l;
  for (int k = 0; k < 16; ++k) {
    const std::uint32_t v = w[k];
    l[4 * k] = static_cast<std::uint8_t>(v);
    l[4 * k + 1] = static_cast<std::uint8_t>(v >> 8);
    l[4 * k + 2] = static_cast<std::uint8_t>(v >> 16);
    l[4 * k + 3] = static_cast<std::uint8_t>(v >> 24);
  }
  return l;
}

// Largest value a port of this C++ type holds (skip chunks).
template <class P>
constexpr std::uint64_t portMax() {
  return std::numeric_limits<std::remove_reference_t<P>>::max();
}

}  // namespace vport

// Thrown when a trace is asked for that this build cannot write.
struct TraceUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <class VTop>
class VerilatedAfuPort final : public AfuPort {
 public:
  static constexpr bool kHasIdle = vport::hasIdle<VTop>;
  static constexpr bool kHasSkip = kHasIdle && vport::hasSkip<VTop>;
  static constexpr bool kHasBusy = vport::hasBusy<VTop>;
  static constexpr bool kCanFst = vport::CanFst<VTop>::value;
  static constexpr bool kCanVcd = vport::CanVcd<VTop>::value;

  explicit VerilatedAfuPort(const AfuPortOptions& o = {}) : ctx_(std::make_unique<VerilatedContext>()) {
    if (!(o.clockMHz > 0)) throw std::invalid_argument("VerilatedAfuPort: clockMHz must be > 0");
    // Model time in the context's precision units (Verilator's default 1 ps).
    const double unitsPerNs = std::pow(10.0, -9 - ctx_->timeprecision());
    periodUnits_ = static_cast<std::uint64_t>(std::llround(1e3 / o.clockMHz * unitsPerNs));
    if (periodUnits_ < 2) periodUnits_ = 2;
    ctx_->traceEverOn(!o.traceFile.empty());
    top_ = std::make_unique<VTop>(ctx_.get(), "afu");
    if (!o.traceFile.empty()) openTrace(o.traceFile);
  }

  ~VerilatedAfuPort() override {
    // Verilator 5.006 unregisters a model's scopes through the *thread's* current context
    // (~VerilatedScope); with several models per thread that may be another model's, freed
    // already (a hang in a mutex of freed memory). Make it this model's own.
    Verilated::threadContextp(ctx_.get());
    if (top_) top_->final();
    closeTrace();  // before the model it refers to
    top_.reset();
  }
  VerilatedAfuPort(const VerilatedAfuPort&) = delete;
  VerilatedAfuPort& operator=(const VerilatedAfuPort&) = delete;

  // Synchronous reset: 5 cycles with reset high, inputs quiet, then released.
  void reset() override {
    top_->reset = 1;
    quietInputs();
    for (int k = 0; k < 5; ++k) {
      (void)evalOutputs();
      clockEdge();
    }
    top_->reset = 0;
    top_->eval();
  }

  void setInputs(const link::LinkToAfu& in) override {
    VTop& t = *top_;
    t.io_rdReq_ready = in.rdReqReady;
    t.io_wrReq_ready = in.wrReqReady;
    t.io_rdResp_valid = in.rdResp.has_value();
    if (in.rdResp) {
      t.io_rdResp_bits_tag = in.rdResp->tag;
      vport::lineToWide(in.rdResp->data, t.io_rdResp_bits_data);
    }
    t.io_wrResp_valid = in.wrResp.has_value();
    if (in.wrResp) t.io_wrResp_bits_tag = in.wrResp->tag;
    t.io_csr_valid = in.csr.has_value();
    if (in.csr) {
      t.io_csr_bits_index = in.csr->index;
      t.io_csr_bits_data = in.csr->data;
    }
  }

  link::AfuToLink evalOutputs() override {
    VTop& t = *top_;
    t.clock = 0;
    ctx_->time(cycle_ * periodUnits_);
    t.eval();
    dump();
    link::AfuToLink out;
    if (t.io_rdReq_valid) out.rdReq = link::ReadReq{t.io_rdReq_bits_addr, t.io_rdReq_bits_tag};
    if (t.io_wrReq_valid)
      out.wrReq = link::WriteReq{t.io_wrReq_bits_addr, t.io_wrReq_bits_tag,
                                 vport::wideToLine(t.io_wrReq_bits_data)};
    return out;
  }

  void clockEdge() override {
    ctx_->time(cycle_ * periodUnits_ + periodUnits_ / 2);
    top_->clock = 1;
    top_->eval();
    dump();
    ++cycle_;
  }

  bool idle() const override {
    if constexpr (kHasIdle) return vport::idleOf(*top_);
    else if constexpr (kHasBusy) return !vport::busyOf(*top_);
    else return false;
  }

  bool reportsIdle() const override { return kHasIdle || kHasBusy; }

  void skipIdleCycles(std::uint64_t n) override {
    if constexpr (kHasSkip) {
      auto& skip = vport::skipCyclesOf(*top_);
      constexpr std::uint64_t maxChunk = vport::portMax<decltype(skip)>();
      while (n > 0) {
        const std::uint64_t k = n < maxChunk ? n : maxChunk;
        if (!vport::idleOf(*top_)) throw std::logic_error("VerilatedAfuPort::skipIdleCycles: the AFU is not idle");
        quietInputs();
        skip = k;
        (void)evalOutputs();
        clockEdge();  // one edge worth k cycles
        skip = 0;
        cycle_ += k - 1;
        n -= k;
      }
    } else {
      AfuPort::skipIdleCycles(n);
    }
  }

  // Clock edges represented so far, reset and skipped cycles included.
  std::uint64_t cycle() const { return cycle_; }
  VTop& model() { return *top_; }
  bool tracing() const { return static_cast<bool>(fst_) || static_cast<bool>(vcd_); }

 private:
  void quietInputs() {
    VTop& t = *top_;
    t.io_rdReq_ready = 0;
    t.io_wrReq_ready = 0;
    t.io_rdResp_valid = 0;
    t.io_wrResp_valid = 0;
    t.io_csr_valid = 0;
  }

  void openTrace(const std::filesystem::path& file) {
    const std::string ext = file.extension().string();
    if (ext != ".fst" && ext != ".vcd")
      throw std::invalid_argument(file.string() + ": a trace file must end in .fst or .vcd");
#if VM_TRACE_FST
    if constexpr (kCanFst) {
      if (ext == ".fst") {
        fst_ = std::make_unique<VerilatedFstC>();
        top_->trace(fst_.get(), 99);
        fst_->open(file.string().c_str());
        if (!fst_->isOpen()) throw std::runtime_error(file.string() + ": cannot open the FST trace");
        return;
      }
    }
#endif
#if VM_TRACE_VCD
    if constexpr (kCanVcd) {
      if (ext == ".vcd") {
        vcd_ = std::make_unique<VerilatedVcdC>();
        top_->trace(vcd_.get(), 99);
        vcd_->open(file.string().c_str());
        if (!vcd_->isOpen()) throw std::runtime_error(file.string() + ": cannot open the VCD trace");
        return;
      }
    }
#endif
    throw TraceUnavailable(file.string() + ": this AFU model was not Verilated with " +
                           (ext == ".fst" ? "FST" : "VCD") + " tracing (it has " +
                           (kCanFst ? "FST" : kCanVcd ? "VCD" : "no") +
                           " tracing); reconfigure host/ with -DCOLLIDE_AFU_TRACE=" +
                           (ext == ".fst" ? "FST" : "VCD"));
  }

  void dump() {
#if VM_TRACE_FST
    if (fst_) fst_->dump(ctx_->time());
#endif
#if VM_TRACE_VCD
    if (vcd_) vcd_->dump(ctx_->time());
#endif
  }

  void closeTrace() {
#if VM_TRACE_FST
    if (fst_) fst_->close();
#endif
#if VM_TRACE_VCD
    if (vcd_) vcd_->close();
#endif
    fst_.reset();
    vcd_.reset();
  }

#if VM_TRACE_FST
  std::unique_ptr<VerilatedFstC> fst_;
#else
  std::unique_ptr<int> fst_;  // placeholder: no FST support in this build
#endif
#if VM_TRACE_VCD
  std::unique_ptr<VerilatedVcdC> vcd_;
#else
  std::unique_ptr<int> vcd_;
#endif
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<VTop> top_;
  std::uint64_t cycle_ = 0;
  std::uint64_t periodUnits_ = 5000;
};

}  // namespace collide::driver
