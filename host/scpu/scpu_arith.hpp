#pragma once
// The SCPU's arithmetic on the host: + - x / sqrt and power-of-two scaling in a compute
// format narrower than or equal to binary64, each one binary64 operation then one rounding
// to the format (RNE, subnormals kept). That is the format's own correctly rounded operation
// when binary64 has at least 2p + 2 significand bits (p the format's; the double-rounding
// bound for + - x / sqrt) or the format is binary64 itself; callers check
// NumberFormat::emulatedExactlyByBinary64. The build never fuses a*b+c (-ffp-contract=off).
//
// The AFU's record bit ARITH is "an operator on the path raised overflow or invalid"
// (docs/scpu.md, "Flags"); overflowOrInvalid() is that bit for the operations done so far.
#include <algorithm>
#include <cmath>
#include <limits>

#include "format/number_format.hpp"

namespace collide::scpu {

// How the SCPU turns p1 - p2 into d and the normal's factor (the manifest's scpu.distance).
enum class DistanceMethod { SqrtThenRecip, Rsqrt, Robust };

// What the host needs to know of an SCPU's arithmetic to reproduce it.
struct ComputeArith {
  format::NumberFormat compute = format::kBinary32;  // the SCPU's format
  format::NumberFormat link = format::kBinary32;     // the link's fields
  DistanceMethod distance = DistanceMethod::SqrtThenRecip;
};

class RoundedArith {
 public:
  explicit RoundedArith(const format::NumberFormat& f) : f_(f) {}

  // x rounded to the format, no flags: for values known to fit (widening, constants).
  double round(double x) const { return format::roundTo(x, f_); }
  // x rounded to the format as a conversion does: a finite value that becomes infinite is OF.
  double convert(double x) { return op(x, x, x); }
  double add(double a, double b) { return op(a + b, a, b); }
  double sub(double a, double b) { return op(a - b, a, b); }
  double mul(double a, double b) { return op(a * b, a, b); }
  // a / b; x / 0 of a finite nonzero x is DZ, which the ARITH bit does not count.
  double div(double a, double b) {
    if (b == 0 && a != 0 && std::isfinite(a)) return round(a / b);
    return op(a / b, a, b);
  }
  double sqrt(double a) { return op(std::sqrt(a), a, a); }
  // x * 2^e as the format's one rounder rounds it (the Robust method's Pow2Scale): exact
  // unless it leaves the normal range; zeros, infinities and NaN pass unchanged.
  double scale(double x, int e) { return std::isfinite(x) && x != 0 ? op(std::ldexp(x, e), x, x) : round(x); }

  bool overflowOrInvalid() const { return ofnv_; }

 private:
  double op(double exact, double a, double b) {
    const double r = round(exact);
    if (std::isnan(r) && !std::isnan(a) && !std::isnan(b)) ofnv_ = true;           // NV: inf - inf, 0 x inf, sqrt(-x)
    else if (std::isinf(r) && std::isfinite(a) && std::isfinite(b)) ofnv_ = true;   // OF
    return r;
  }

  format::NumberFormat f_;
  bool ofnv_ = false;
};

// The Robust method's scale exponent: that of the largest |component|, 0 if all are zero or
// any is not finite (ScpuModel.scaleExponent).
inline int scaleExponent(const double u[3]) {
  int e = std::numeric_limits<int>::min();
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(u[k])) return 0;
    if (u[k] != 0) e = std::max(e, std::ilogb(u[k]));
  }
  return e == std::numeric_limits<int>::min() ? 0 : e;
}

}  // namespace collide::scpu
