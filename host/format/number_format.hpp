#pragma once
// Binary floating-point formats narrower than (or equal to) IEEE binary64, and exact
// conversions between them and double: the link's fields (binary16, bfloat16, binary32,
// binary64) and the SCPU's compute formats. A format is (exponent bits, significand bits
// with the hidden bit), IEEE-754 encoded, subnormals kept, one canonical NaN (positive, quiet
// bit set), as the AFU's own arithmetic (docs/fp.md).
#include <cstdint>
#include <string>

namespace collide::format {

struct NumberFormat {
  int expBits = 11, sigBits = 53;

  int width() const { return expBits + sigBits; }
  int maxExp() const { return (1 << (expBits - 1)) - 1; }
  int minExp() const { return 2 - (1 << (expBits - 1)); }
  double maxFinite() const;
  bool isBinary64() const { return expBits == 11 && sigBits == 53; }
  // Whether one binary64 operation (+ - x) followed by one rounding to this format equals the
  // format's own correctly rounded operation: binary64 has at least 2p + 2 significand bits
  // (the double-rounding bound for + - x / sqrt), or this is binary64 itself.
  bool emulatedExactlyByBinary64() const { return isBinary64() || 2 * sigBits + 2 <= 53; }
  bool operator==(const NumberFormat& o) const { return expBits == o.expBits && sigBits == o.sigBits; }
  bool operator!=(const NumberFormat& o) const { return !(*this == o); }
};

inline constexpr NumberFormat kBinary16{5, 11};
inline constexpr NumberFormat kBFloat16{8, 8};
inline constexpr NumberFormat kBinary32{8, 24};
inline constexpr NumberFormat kBinary64{11, 53};

std::string describe(const NumberFormat& f);  // "binary32", ..., else "e<E>m<M>"

// x rounded to f, round to nearest even, subnormals kept; overflow gives a signed infinity;
// zeros keep their sign; NaN gives the canonical NaN. `sticky`: the true value lies strictly
// beyond x in magnitude (x is its truncation, e.g. a decimal parsed toward zero), so a tie
// between two f values is not a tie and rounds away from zero.
double roundTo(double x, const NumberFormat& f, bool sticky = false);
// Whether x (a double) is a value of f.
bool representable(double x, const NumberFormat& f);

// The bit pattern of x in f (x rounded first, as roundTo); NaN encodes canonically.
std::uint64_t encode(double x, const NumberFormat& f);
// The exact value of a bit pattern of f.
double decode(std::uint64_t bits, const NumberFormat& f);

// Parses a decimal or C99 hex float straight into f with one rounding (RNE). glibc's strtod
// honours the rounding mode, so the text is read rounded down and up: the truncation and
// whether it was exact make the sticky bit, and no tie is broken twice. Returns false if
// `text` is not wholly a number.
bool parseInto(const char* text, const NumberFormat& f, double& out);

}  // namespace collide::format
