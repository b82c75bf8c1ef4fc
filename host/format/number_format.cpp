#include "format/number_format.hpp"

#include <cfenv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace collide::format {

double NumberFormat::maxFinite() const {
  return std::ldexp(2.0 - std::ldexp(1.0, 1 - sigBits), maxExp());
}

std::string describe(const NumberFormat& f) {
  if (f == kBinary16) return "binary16";
  if (f == kBFloat16) return "bfloat16";
  if (f == kBinary32) return "binary32";
  if (f == kBinary64) return "binary64";
  return "e" + std::to_string(f.expBits) + "m" + std::to_string(f.sigBits);
}

double roundTo(double x, const NumberFormat& f, bool sticky) {
  if (std::isnan(x)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(x) || x == 0) return x;
  if (f.isBinary64() && !sticky) return x;
  // binary32: the hardware conversion is this rounding (RNE in the default mode, subnormals
  // kept, overflow to infinity), and far cheaper than the general path below.
  if (f.expBits == 8 && f.sigBits == 24 && !sticky) return static_cast<double>(static_cast<float>(x));
  // Quantum of x's binade in f (subnormals share the smallest normal binade's quantum).
  const int e = std::max(std::ilogb(x), f.minExp());
  const int q = e - (f.sigBits - 1);
  const double scaled = std::ldexp(x, -q);  // exact: a power-of-two scaling of a double
  double r = std::nearbyint(scaled);        // RNE in the default rounding mode
  if (sticky && std::fabs(scaled - std::trunc(scaled)) == 0.5) r = std::trunc(scaled) + (x > 0 ? 1 : -1);
  const double y = std::ldexp(r, q);
  if (std::fabs(y) > f.maxFinite()) return std::copysign(std::numeric_limits<double>::infinity(), x);
  return y;
}

bool representable(double x, const NumberFormat& f) {
  if (std::isnan(x)) return true;
  return roundTo(x, f) == x;
}

std::uint64_t encode(double v, const NumberFormat& f) {
  const int fracBits = f.sigBits - 1;
  const std::uint64_t expAll = (std::uint64_t{1} << f.expBits) - 1;
  const std::uint64_t signBit = std::uint64_t{1} << (f.width() - 1);
  if (std::isnan(v)) return (expAll << fracBits) | (std::uint64_t{1} << (fracBits - 1));
  const double x = roundTo(v, f);
  const std::uint64_t sign = std::signbit(x) ? signBit : 0;
  if (std::isinf(x)) return sign | (expAll << fracBits);
  if (x == 0) return sign;
  const double a = std::fabs(x);
  const int e = std::ilogb(a);
  if (e < f.minExp()) {  // subnormal: the fraction counts quanta of 2^(minExp - fracBits)
    const auto frac = static_cast<std::uint64_t>(std::ldexp(a, fracBits - f.minExp()));
    return sign | frac;
  }
  const auto sig = static_cast<std::uint64_t>(std::ldexp(a, fracBits - e));  // in [2^fracBits, 2^sigBits)
  const std::uint64_t biased = static_cast<std::uint64_t>(e + f.maxExp());
  return sign | (biased << fracBits) | (sig & ((std::uint64_t{1} << fracBits) - 1));
}

double decode(std::uint64_t bits, const NumberFormat& f) {
  const int fracBits = f.sigBits - 1;
  const std::uint64_t expAll = (std::uint64_t{1} << f.expBits) - 1;
  const bool neg = (bits >> (f.width() - 1)) & 1;
  const std::uint64_t ex = (bits >> fracBits) & expAll;
  const std::uint64_t frac = bits & ((std::uint64_t{1} << fracBits) - 1);
  double v;
  if (ex == expAll) v = frac ? std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::infinity();
  else if (ex == 0) v = std::ldexp(static_cast<double>(frac), f.minExp() - fracBits);
  else v = std::ldexp(static_cast<double>(frac | (std::uint64_t{1} << fracBits)), static_cast<int>(ex) - f.maxExp() - fracBits);
  return neg ? -v : v;
}

bool parseInto(const char* text, const NumberFormat& f, double& out) {
  char* end = nullptr;
  if (f.isBinary64() || f == kBinary32) {
    // One rounding straight from the text: strtod, or strtof for binary32.
    out = f == kBinary32 ? static_cast<double>(std::strtof(text, &end)) : std::strtod(text, &end);
    return end != text && *end == '\0';
  }
  // Read the text rounded down and rounded up: equal means exact; else the true value lies
  // strictly between two adjacent doubles, and the one nearer zero is its truncation.
  const int mode = std::fegetround();
  std::fesetround(FE_DOWNWARD);
  const double lo = std::strtod(text, &end);
  std::fesetround(FE_UPWARD);
  const double hi = std::strtod(text, nullptr);
  std::fesetround(mode);
  if (end == text || *end != '\0') return false;
  const bool inexact = lo != hi && !(std::isnan(lo) && std::isnan(hi));
  const double t = std::fabs(lo) < std::fabs(hi) ? lo : hi;
  out = roundTo(t, f, inexact);
  return true;
}

}  // namespace collide::format
