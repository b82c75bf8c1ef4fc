#include "driver/contact_rebuild.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "afu_contract.hpp"

namespace collide::driver {

namespace {
using format::NumberFormat;

// + - x in the compute format: one binary64 operation, one rounding (exact by the 2p+2
// rule, or binary64 itself), NaN canonical as the SCPU's operators return it.
class Arith {
 public:
  explicit Arith(const NumberFormat& f) : f_(f) {}
  double round(double x) const { return format::roundTo(x, f_); }
  double add(double a, double b) const { return round(a + b); }
  double sub(double a, double b) const { return round(a - b); }
  double mul(double a, double b) const { return round(a * b); }
  // x * 2^e rounded as the format's rounder does (the Robust method's Pow2Scale).
  double scale(double x, int e) const { return std::isfinite(x) && x != 0 ? round(std::ldexp(x, e)) : round(x); }

 private:
  NumberFormat f_;
};

// The Robust method's scale exponent: that of the largest |component|, 0 if all are zero or
// any is not finite (ScpuModel.scaleExponent).
int scaleExponent(const double u[3]) {
  int e = std::numeric_limits<int>::min();
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(u[k])) return 0;
    if (u[k] != 0) e = std::max(e, std::ilogb(u[k]));
  }
  return e == std::numeric_limits<int>::min() ? 0 : e;
}
}  // namespace

void rebuildContact(const ComputeArith& a, const double s1[4], const double s2[4], double d, double w,
                    std::uint8_t flags, double out[7]) {
  std::fill(out, out + 7, 0.0);
  if (!(flags & contract::REC_HIT)) return;
  const Arith c(a.compute);
  // link -> compute (the SCPU's input conversion; the identity when the formats agree)
  double p1[4], p2[4];
  for (int k = 0; k < 4; ++k) { p1[k] = c.round(s1[k]); p2[k] = c.round(s2[k]); }
  const double rs = c.add(p1[3], p2[3]);
  const unsigned kind = (flags >> contract::REC_KIND_SHIFT) & contract::REC_KIND_MASK;
  if (kind == contract::KIND_COINCIDENT) {
    out[0] = p1[0]; out[1] = p1[1]; out[2] = p1[2];
    out[3] = 1.0; out[6] = rs;
    return;
  }
  if (kind != contract::KIND_CONTACT) return;
  double u[3] = {c.sub(p1[0], p2[0]), c.sub(p1[1], p2[1]), c.sub(p1[2], p2[2])};
  if (a.distance == DistanceMethod::Robust) {
    const int e = scaleExponent(u);
    for (double& x : u) x = c.scale(x, -e);
  }
  const double rdiff = c.sub(p2[3], p1[3]);
  const double depth = c.sub(rs, d);
  const double k = c.mul(0.5, c.sub(rdiff, d));
  for (int i = 0; i < 3; ++i) {
    const double n = c.mul(u[i], w);
    out[i] = c.add(p1[i], c.mul(n, k));
    out[3 + i] = n;
  }
  out[6] = depth;
}

}  // namespace collide::driver
