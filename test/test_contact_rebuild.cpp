// The derived record layout's host side: from the spheres as the link carries them, the
// record's d and w and its flags, driver::rebuildContact must give exactly the full record
// (position, normal, depth) that the Scala golden model computes, for every link format and
// distance method: golden vectors written by the golden model (test/vectors/README.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "afu_contract.hpp"
#include "driver/contact_rebuild.hpp"
#include "support/golden_vectors.hpp"

using namespace collide;
using collide::driver::ComputeArith;
using collide::driver::DistanceMethod;

namespace {
bool sameBits(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

struct Case {
  const char* file;
  LinkFormat link;
  format::NumberFormat compute;
  DistanceMethod distance;
};

void checkFile(const Case& c) {
  const auto g = test::readGoldenVectors(std::string(COLLIDE_TEST_VECTORS_DIR) + "/" + c.file, c.link);
  const ComputeArith a{c.compute, numberFormat(c.link), c.distance};
  std::size_t contacts = 0, coincident = 0;
  for (std::size_t k = 0; k < g.expected.size(); ++k) {
    const auto& e = g.expected[k];
    ASSERT_TRUE(e.flags && e.d && e.w) << c.file << ": needs flags, d and w columns";
    const std::size_t i = g.pairs.i[k], j = g.pairs.j[k];
    const double s1[4] = {g.spheres.x[i], g.spheres.y[i], g.spheres.z[i], g.spheres.r[i]};
    const double s2[4] = {g.spheres.x[j], g.spheres.y[j], g.spheres.z[j], g.spheres.r[j]};
    double out[7];
    driver::rebuildContact(a, s1, s2, *e.d, *e.w, static_cast<std::uint8_t>(*e.flags), out);
    const unsigned kind = (*e.flags >> contract::REC_KIND_SHIFT) & contract::REC_KIND_MASK;
    contacts += e.hit && kind == contract::KIND_CONTACT;
    coincident += e.hit && kind == contract::KIND_COINCIDENT;
    for (int f = 0; f < 7; ++f)
      ASSERT_TRUE(sameBits(out[f], e.v[f])) << c.file << ":" << e.line << ": field " << contract::kFullFields[f]
                                             << " rebuilt " << std::hexfloat << out[f] << ", golden " << e.v[f];
  }
  // Not vacuous: the files hold thousands of contacts and the coincident cases.
  EXPECT_GT(contacts, 300u) << c.file;
  EXPECT_GT(coincident, 0u) << c.file;
}
}  // namespace

TEST(ContactRebuild, Binary32SqrtThenRecipIsTheFullRecordBitForBit) {
  checkFile({"fp32_default.csv", LinkFormat::Binary32, format::kBinary32, DistanceMethod::SqrtThenRecip});
}
TEST(ContactRebuild, Binary32RsqrtIsTheFullRecordBitForBit) {
  checkFile({"fp32-rsqrt-dr.csv", LinkFormat::Binary32, format::kBinary32, DistanceMethod::Rsqrt});
}
TEST(ContactRebuild, Binary32RobustScalingIsTheFullRecordBitForBit) {
  checkFile({"fp32-robust.csv", LinkFormat::Binary32, format::kBinary32, DistanceMethod::Robust});
}
TEST(ContactRebuild, Binary32NewtonRaphsonRootsAreTheFullRecordBitForBit) {
  checkFile({"fp32-nr.csv", LinkFormat::Binary32, format::kBinary32, DistanceMethod::SqrtThenRecip});
}
TEST(ContactRebuild, Fp24OnABinary32LinkIsTheFullRecordBitForBit) {
  checkFile({"fp24.csv", LinkFormat::Binary32, format::NumberFormat{8, 16}, DistanceMethod::SqrtThenRecip});
}
TEST(ContactRebuild, Binary16IsTheFullRecordBitForBit) {
  checkFile({"fp16.csv", LinkFormat::Binary16, format::kBinary16, DistanceMethod::SqrtThenRecip});
}
TEST(ContactRebuild, Binary16RobustScalingIsTheFullRecordBitForBit) {
  checkFile({"fp16-robust.csv", LinkFormat::Binary16, format::kBinary16, DistanceMethod::Robust});
}
TEST(ContactRebuild, BFloat16IsTheFullRecordBitForBit) {
  checkFile({"bf16.csv", LinkFormat::BFloat16, format::kBFloat16, DistanceMethod::SqrtThenRecip});
}
TEST(ContactRebuild, Binary64IsTheFullRecordBitForBit) {
  checkFile({"fp64.csv", LinkFormat::Binary64, format::kBinary64, DistanceMethod::SqrtThenRecip});
}
