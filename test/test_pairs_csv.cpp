// Vector-mode CSV: decimal and hex input, link-format output, errors with line numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <sstream>
#include <vector>

#include "cli/pairs_csv.hpp"

using namespace collide;
using namespace collide::cli;

namespace {
std::string parseError(const std::string& text, LinkFormat f = LinkFormat::Binary32) {
  std::istringstream in(text);
  SphereTable s;
  PairList p;
  std::vector<std::uint8_t> unfit;
  try {
    readPairsCsv(in, "in.csv", f, s, p, unfit);
  } catch (const CsvError& e) {
    return e.what();
  }
  return "(no error)";
}
const std::string kHeader = "x1,y1,z1,r1,x2,y2,z2,r2\n";
}  // namespace

TEST(PairsCsv, ParsesDecimalAndHexFloats) {
  std::istringstream in(kHeader + "0.1,0x1.8p+1, -2 ,1e-3,0,0,0,1\n\n  \n0x1p-149,-0,inf,nan,1,2,3,4\r\n");
  SphereTable s;
  PairList p;
  std::vector<std::uint8_t> unfit;
  readPairsCsv(in, "in.csv", LinkFormat::Binary32, s, p, unfit);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p.i[1], 2u);
  EXPECT_EQ(p.j[1], 3u);
  EXPECT_EQ(s.x[0], static_cast<double>(0.1f));  // one rounding, straight to binary32
  EXPECT_NE(s.x[0], 0.1);
  EXPECT_EQ(s.y[0], 3.0);
  EXPECT_EQ(s.z[0], -2.0);
  EXPECT_EQ(s.r[0], static_cast<double>(1e-3f));
  EXPECT_EQ(s.x[2], static_cast<double>(0x1p-149f));  // subnormal: accepted
  EXPECT_TRUE(std::signbit(s.y[2]));
  EXPECT_TRUE(std::isinf(s.z[2]));
  EXPECT_TRUE(std::isnan(s.r[2]));

  std::istringstream in64(kHeader + "0.1,0,0,1,0,0,0,1\n");
  SphereTable s64;
  PairList p64;
  readPairsCsv(in64, "in.csv", LinkFormat::Binary64, s64, p64, unfit);
  EXPECT_EQ(s64.x[0], 0.1);
}

TEST(PairsCsv, ErrorsNameTheLine) {
  EXPECT_EQ(parseError(""), "in.csv:1: empty input: expected the header 'x1,y1,z1,r1,x2,y2,z2,r2'");
  EXPECT_EQ(parseError("x1,y1,z1\n"), "in.csv:1: expected the header 'x1,y1,z1,r1,x2,y2,z2,r2', got 'x1,y1,z1'");
  EXPECT_EQ(parseError(kHeader + "1,2,3,4,5,6,7,8\n1,2,3,4,5,6,7\n"), "in.csv:3: expected 8 fields, got 7");
  EXPECT_EQ(parseError(kHeader + "\n1,2,3,4,5,6,7,8,9\n"), "in.csv:3: expected 8 fields, got 9");
  EXPECT_EQ(parseError(kHeader + "1,2,3,4,abc,6,7,8\n"), "in.csv:2: x2: not a number: 'abc'");
  EXPECT_EQ(parseError(kHeader + "1,2,3,4,5,6,7,\n"), "in.csv:2: r2: empty field");
  EXPECT_EQ(parseError(kHeader + "1,2,3,4,5,6,7,8\n1,2,3,1.5.2,5,6,7,8\n"), "in.csv:3: r1: not a number: '1.5.2'");
}

// A value the format cannot hold is kept as rounded and its sphere marked, never a
// whole-file error: the pair is flagged (collidePairs), every other pair is computed.
TEST(PairsCsv, AValueThatDoesNotFitMarksItsSphereNotTheFile) {
  std::istringstream in(kHeader + "1e39,2,3,4,5,6,7,8\n0,0,0,1e-50,0,0,0,1\n0,1e-50,0,1,0,0,0,inf\n"
                                  "1,2,3,4,5,6,7,8\n");
  SphereTable s;
  PairList p;
  std::vector<std::uint8_t> unfit;
  readPairsCsv(in, "in.csv", LinkFormat::Binary32, s, p, unfit);
  ASSERT_EQ(p.size(), 4u);
  ASSERT_EQ(unfit.size(), s.size());
  EXPECT_TRUE(std::isinf(s.x[0]));
  EXPECT_EQ(unfit[0], 1) << "a finite literal that became infinite";
  EXPECT_EQ(unfit[1], 0);
  EXPECT_EQ(s.r[2], 0.0);
  EXPECT_EQ(unfit[2], 1) << "a non-zero radius that became zero";
  EXPECT_EQ(unfit[4], 0) << "a coordinate that became zero is still the nearest value";
  EXPECT_EQ(unfit[5], 0) << "a literal infinity fits: it is a non-finite input, not an overflow";
  EXPECT_EQ(unfit[6] + unfit[7], 0);
  // binary16 tops out at 65504; binary64 holds 1e39.
  std::istringstream in16(kHeader + "1e5,0,0,1,0,0,0,1\n"), in64(kHeader + "1e39,0,0,1,0,0,0,1\n");
  SphereTable s16, s64;
  PairList p16, p64;
  std::vector<std::uint8_t> u16, u64;
  readPairsCsv(in16, "in.csv", LinkFormat::Binary16, s16, p16, u16);
  readPairsCsv(in64, "in.csv", LinkFormat::Binary64, s64, p64, u64);
  EXPECT_EQ(u16[0], 1);
  EXPECT_EQ(u64[0], 0);
  EXPECT_EQ(s64.x[0], 1e39);
}

TEST(PairsCsv, WritesHexFloatsInTheLinkFormat) {
  ContactSet c;
  c.resize(2);
  c.format = LinkFormat::Binary32;
  c.hit[1] = 1;
  c.flags[1] = 3;  // hit, kind contact
  c.px[1] = static_cast<float>(0.1);
  c.nx[1] = 1.0;
  c.depth[1] = 0x1.0p-21;
  std::ostringstream out;
  writeContactsCsv(out, c);
  EXPECT_EQ(out.str(),
            "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n"
            "0,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0\n"
            "1,1,0x1.99999ap-4,0x0p+0,0x0p+0,0x1p+0,0x0p+0,0x0p+0,0x1p-21,3\n");
  EXPECT_EQ(hexFloat(1.0 + 0x1p-10, LinkFormat::Binary16), "0x1.004p+0");
  EXPECT_EQ(hexFloat(0.1, LinkFormat::Binary64), "0x1.999999999999ap-4");
}

TEST(PairsCsv, AByteOrderMarkBeforeTheHeaderIsAccepted) {
  std::istringstream in("\xEF\xBB\xBF" + kHeader + "0,0,0,1,0,0,0,2\n");
  SphereTable s;
  PairList p;
  std::vector<std::uint8_t> unfit;
  readPairsCsv(in, "in.csv", LinkFormat::Binary32, s, p, unfit);
  EXPECT_EQ(p.size(), 1u);
  // Elsewhere an invisible byte is named as such, not shown as an identical header.
  EXPECT_EQ(parseError("x1,y1,z1,r1,x2,y2,z2,r2\xC2\xA0\n"),
            "in.csv:1: expected the header 'x1,y1,z1,r1,x2,y2,z2,r2', got 'x1,y1,z1,r1,x2,y2,z2,r2\xC2\xA0' "
            "(it holds control or non-ASCII bytes)");
}

TEST(PairsCsv, AnOverlongLineIsAnErrorNotAnAllocation) {
  const std::string e = parseError(kHeader + std::string(10'000'000, '1'));  // no newline
  EXPECT_EQ(e.rfind("in.csv:2: line longer than 65536 bytes (a row is 8 numbers): '1111", 0), 0u) << e.substr(0, 200);
  EXPECT_LT(e.size(), 200u);
}
