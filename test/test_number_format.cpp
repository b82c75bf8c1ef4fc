// format::NumberFormat: rounding, encoding and parsing into the link's narrow formats,
// checked against independent oracles: GCC's _Float16 (IEEE binary16 conversions in the
// compiler's runtime), bfloat16 as the top half of a binary32 (round to nearest even on the
// dropped half), and every binary16 pattern exhaustively.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

#include "format/number_format.hpp"
#include "support/test_seed.hpp"

using namespace collide::format;

namespace {
std::uint32_t bitsOf(float f) { std::uint32_t u; std::memcpy(&u, &f, 4); return u; }
float floatOf(std::uint32_t u) { float f; std::memcpy(&f, &u, 4); return f; }
// bfloat16 oracle: binary32 -> bfloat16 by rounding the low 16 bits to nearest even.
std::uint16_t bf16Of(float f) {
  const std::uint32_t u = bitsOf(f);
  if (std::isnan(f)) return 0x7FC0;
  return static_cast<std::uint16_t>((u + 0x7FFF + ((u >> 16) & 1)) >> 16);
}
std::uint16_t f16Bits(_Float16 h) { std::uint16_t u; std::memcpy(&u, &h, 2); return u; }
}  // namespace

TEST(NumberFormat, DecodesEveryBinary16PatternAsTheCompilerDoesAndEncodesItBack) {
  int finite = 0;
  for (std::uint32_t b = 0; b < 0x10000; ++b) {
    _Float16 h;
    const std::uint16_t u = static_cast<std::uint16_t>(b);
    std::memcpy(&h, &u, 2);
    const double want = static_cast<double>(h);
    const double got = decode(b, kBinary16);
    if (std::isnan(want)) { ASSERT_TRUE(std::isnan(got)) << std::hex << b; continue; }
    ASSERT_EQ(std::signbit(got), std::signbit(want)) << std::hex << b;
    ASSERT_EQ(got, want) << std::hex << b;
    ASSERT_EQ(encode(got, kBinary16), b) << std::hex << b;
    ASSERT_TRUE(representable(got, kBinary16));
    ++finite;
  }
  EXPECT_EQ(finite, 65536 - 2 * 1023);  // all but the 2046 NaNs (infinities count as values)
}

TEST(NumberFormat, RoundsDoublesToBinary16AsTheCompilerDoes) {
  std::mt19937_64 rng(collide::test::testSeed(16));
  std::uniform_int_distribution<int> ex(-30, 17);
  std::uniform_real_distribution<double> m(1.0, 2.0);
  for (int k = 0; k < 200000; ++k) {
    double x = std::ldexp(m(rng), ex(rng)) * (rng() & 1 ? -1 : 1);
    if (k % 7 == 0) x = decode(rng() & 0x7BFF, kBinary16) + std::ldexp(1.0, -25 + static_cast<int>(rng() % 20));  // near ties
    const _Float16 h = static_cast<_Float16>(x);  // GCC: one RNE rounding from double
    ASSERT_EQ(encode(x, kBinary16), f16Bits(h)) << std::hexfloat << x;
    ASSERT_EQ(roundTo(x, kBinary16), static_cast<double>(h)) << std::hexfloat << x;
  }
}

TEST(NumberFormat, RoundsBinary32ValuesToBFloat16AsTheTopHalfRoundsToNearestEven) {
  std::mt19937_64 rng(collide::test::testSeed(8));
  for (int k = 0; k < 200000; ++k) {
    std::uint32_t u = static_cast<std::uint32_t>(rng());
    if ((u & 0x7F800000u) == 0x7F800000u) u &= 0xBFFFFFFFu;  // finite only
    if (k % 5 == 0) u = (u & 0xFFFF0000u) | 0x8000u;         // exact ties
    const float f = floatOf(u);
    ASSERT_EQ(encode(f, kBFloat16), bf16Of(f)) << std::hexfloat << f;
  }
}

TEST(NumberFormat, OverflowsToInfinityKeepsZeroSignsAndGivesOneNaN) {
  EXPECT_EQ(roundTo(65504.0, kBinary16), 65504.0);
  EXPECT_EQ(roundTo(65519.99, kBinary16), 65504.0);
  EXPECT_TRUE(std::isinf(roundTo(65520.0, kBinary16)));        // the tie above max rounds to infinity
  EXPECT_EQ(roundTo(-1e39, kBFloat16), -INFINITY);
  EXPECT_EQ(roundTo(3.39e38, kBFloat16), 3.3895313892515355e38);  // bfloat16 largest finite
  EXPECT_EQ(roundTo(-1e-30, kBinary16), 0.0);
  EXPECT_TRUE(std::signbit(roundTo(-1e-30, kBinary16)));
  EXPECT_EQ(encode(-0.0, kBinary16), 0x8000u);
  EXPECT_EQ(encode(std::nan(""), kBinary16), 0x7E00u);
  EXPECT_EQ(encode(-std::nan(""), kBFloat16), 0x7FC0u);
  EXPECT_EQ(encode(std::ldexp(1.0, -24), kBinary16), 1u);       // the smallest subnormal
  EXPECT_EQ(roundTo(std::ldexp(1.0, -25), kBinary16), 0.0);     // half of it: ties to even (zero)
  EXPECT_EQ(roundTo(std::ldexp(1.5, -25), kBinary16), std::ldexp(1.0, -24));
}

TEST(NumberFormat, ParsesDecimalTextWithOneRoundingNotTwo) {
  double v = 0;
  // 1 + 2^-11 is the exact tie between 1 and 1 + 2^-10 in binary16; a digit beyond breaks it.
  ASSERT_TRUE(parseInto("1.00048828125", kBinary16, v));
  EXPECT_EQ(v, 1.0);
  ASSERT_TRUE(parseInto("1.000488281250000000000001", kBinary16, v));  // strtod alone would say 1 + 2^-11
  EXPECT_EQ(v, 1.0 + std::ldexp(1.0, -10));
  ASSERT_TRUE(parseInto("-1.000488281250000000000001", kBinary16, v));
  EXPECT_EQ(v, -1.0 - std::ldexp(1.0, -10));
  ASSERT_TRUE(parseInto("0x1.002p+0", kBinary16, v));  // ties go to even
  EXPECT_EQ(v, 1.0);
  ASSERT_TRUE(parseInto("0x1.006p+0", kBinary16, v));
  EXPECT_EQ(v, 1.0 + std::ldexp(1.0, -9));
  ASSERT_TRUE(parseInto("1e9", kBinary16, v));
  EXPECT_TRUE(std::isinf(v));
  ASSERT_TRUE(parseInto("inf", kBFloat16, v));
  EXPECT_TRUE(std::isinf(v));
  EXPECT_FALSE(parseInto("1.0x", kBinary16, v));
  EXPECT_FALSE(parseInto("", kBinary16, v));
  // The rounding mode is restored.
  ASSERT_TRUE(parseInto("0.1", kBinary16, v));
  EXPECT_EQ(0.1 + 0.2, 0.30000000000000004);
}
