// The C++ SCPU model as the DPI-C function the simulation-only SCPU calls
// (collide.scpu.ScpuModelUnit, generated with --scpu-impl model): one pair in, in the link
// format's bit patterns; its result out, as the RTL's ScpuOut would carry it. Part of every
// Verilated AFU library; only a model AFU's Verilog imports it.
#include <cstdint>

#include "afu_contract.hpp"
#include "format/number_format.hpp"
#include "scpu/scpu_model.hpp"

namespace {
constexpr int kOverflow = 1 << 2;  // collide.fp.FpFlags.Overflow: the AFU reads only OF | NV (ARITH)
}

// Signature as Verilator maps the import: int -> int, longint -> long long, outputs by pointer.
extern "C" void collide_scpu_model(int computeExp, int computeSig, int linkExp, int linkSig, int distance,
                                   long long x1, long long y1, long long z1, long long r1, long long x2, long long y2,
                                   long long z2, long long r2, long long* px, long long* py, long long* pz,
                                   long long* nx, long long* ny, long long* nz, long long* depth, long long* d,
                                   long long* nw, int* info) {
  using namespace collide;
  const format::NumberFormat cf{computeExp, computeSig}, lf{linkExp, linkSig};
  const scpu::ComputeArith a{cf, lf, static_cast<scpu::DistanceMethod>(distance)};
  auto in = [&](long long b) { return format::decode(static_cast<std::uint64_t>(b), lf); };
  const double s1[4] = {in(x1), in(y1), in(z1), in(r1)}, s2[4] = {in(x2), in(y2), in(z2), in(r2)};
  const auto r = scpu::collidePair(a, s1, s2);
  auto out = [&](double v) { return static_cast<long long>(format::encode(v, lf)); };
  long long* fields[7] = {px, py, pz, nx, ny, nz, depth};
  for (int k = 0; k < 7; ++k) *fields[k] = out(r.v[k]);
  *d = out(r.d);
  *nw = out(r.w);
  // info: bit 0 hit, bits 1..2 kind, bit 3 a non-finite input, bits 8..12 the FpFlags
  *info = (r.hit ? 1 : 0) | static_cast<int>(r.kind << 1) | ((r.flags & contract::REC_NONFINITE) ? 1 << 3 : 0) |
          ((r.flags & contract::REC_ARITH) ? kOverflow << 8 : 0);
}
