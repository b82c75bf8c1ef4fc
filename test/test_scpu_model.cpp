// The SCPU on the CPU (scpu/scpu_model.hpp, the `model:<preset>` backend) against the Scala
// golden model's vectors (test/vectors): every pair's hit, kind, flags byte, full record and
// derived d and w, bit for bit, for every preset it claims; the presets it does not claim are
// refused with the reason; and the backend does what `collide pairs` and scenes need.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "afu_contract.hpp"
#include "collide/backend_factory.hpp"
#include "collide/input_policy.hpp"
#include "collide/model_backend.hpp"
#include "scpu/scpu_model.hpp"
#include "support/error_of.hpp"
#include "support/golden_vectors.hpp"

using namespace collide;

namespace {
bool sameBits(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

std::string vectorFile(const std::string& preset) {
  return std::string(COLLIDE_TEST_VECTORS_DIR) + "/" + (preset == "fp32" ? "fp32_default" : preset) + ".csv";
}

// Every row of the preset's vectors through collidePair and through the backend (one batch).
void checkPreset(const std::string& name) {
  const auto& p = scpu::emulatedPreset(name);
  const auto g = test::readGoldenVectors(vectorFile(name), p.link);
  ModelBackend backend(name);
  ContactSet batch;
  backend.collide(g.spheres, g.pairs, batch);
  ASSERT_EQ(batch.size(), g.pairs.size());
  std::size_t contacts = 0, coincident = 0, arith = 0;
  for (std::size_t k = 0; k < g.expected.size(); ++k) {
    const auto& e = g.expected[k];
    ASSERT_TRUE(e.flags && e.d && e.w) << name << ": needs flags, d and w columns";
    const std::size_t i = g.pairs.i[k], j = g.pairs.j[k];
    const double s1[4] = {g.spheres.x[i], g.spheres.y[i], g.spheres.z[i], g.spheres.r[i]};
    const double s2[4] = {g.spheres.x[j], g.spheres.y[j], g.spheres.z[j], g.spheres.r[j]};
    const auto r = scpu::collidePair(p.arith, s1, s2);
    const std::string at = name + ":" + std::to_string(e.line);
    // The vectors print a signaling NaN as NaN, so a row with a NaN input may be one whose
    // NaN signals (NV: ARITH) or not; the host only ever sends quiet NaNs. Such rows' ARITH
    // bit is not pinned here; everything else is.
    bool nanInput = false;
    for (int c = 0; c < 4; ++c) nanInput = nanInput || std::isnan(s1[c]) || std::isnan(s2[c]);
    const unsigned mask = nanInput ? ~unsigned{contract::REC_ARITH} : ~0u;
    ASSERT_EQ(r.hit, e.hit) << at;
    ASSERT_EQ(r.flags & mask, *e.flags & mask) << at << ": flags";
    for (int f = 0; f < 7; ++f)
      ASSERT_TRUE(sameBits(r.v[f], e.v[f])) << at << ": field " << contract::kFullFields[f] << " model "
                                            << std::hexfloat << r.v[f] << ", golden " << e.v[f];
    ASSERT_TRUE(sameBits(r.d, *e.d)) << at << ": d " << std::hexfloat << r.d << ", golden " << *e.d;
    ASSERT_TRUE(sameBits(r.w, *e.w)) << at << ": w " << std::hexfloat << r.w << ", golden " << *e.w;
    // The backend: the same values, and the same flags (no input of the vectors is out of
    // the link format's range: they are link-format values already).
    ASSERT_EQ(batch.hit[k], e.hit ? 1 : 0) << at;
    ASSERT_EQ(batch.flags[k] & mask, *e.flags & mask) << at;
    const double got[7] = {batch.px[k], batch.py[k], batch.pz[k], batch.nx[k], batch.ny[k], batch.nz[k], batch.depth[k]};
    for (int f = 0; f < 7; ++f) ASSERT_TRUE(sameBits(got[f], e.v[f])) << at << ": backend field " << f;
    const unsigned kind = (*e.flags >> contract::REC_KIND_SHIFT) & contract::REC_KIND_MASK;
    contacts += e.hit && kind == contract::KIND_CONTACT;
    coincident += e.hit && kind == contract::KIND_COINCIDENT;
    arith += !nanInput && (*e.flags & contract::REC_ARITH) != 0;
  }
  // Not vacuous: thousands of contacts, the coincident cases, and overflowing ones.
  EXPECT_GT(contacts, 300u) << name;
  EXPECT_GT(coincident, 0u) << name;
  EXPECT_GT(arith, 0u) << name;
}
}  // namespace

TEST(ScpuModelCpp, Fp32IsTheGoldenModelBitForBit) { checkPreset("fp32"); }
TEST(ScpuModelCpp, Fp32RobustIsTheGoldenModelBitForBit) { checkPreset("fp32-robust"); }
TEST(ScpuModelCpp, Fp24OnABinary32LinkIsTheGoldenModelBitForBit) { checkPreset("fp24"); }
TEST(ScpuModelCpp, Fp16IsTheGoldenModelBitForBit) { checkPreset("fp16"); }
TEST(ScpuModelCpp, Fp16RobustIsTheGoldenModelBitForBit) { checkPreset("fp16-robust"); }
TEST(ScpuModelCpp, Bf16IsTheGoldenModelBitForBit) { checkPreset("bf16"); }
TEST(ScpuModelCpp, Fp64IsTheGoldenModelBitForBit) { checkPreset("fp64"); }

TEST(ScpuModelCpp, PresetsItCannotReproduceAreRefusedWithTheReason) {
  EXPECT_NE(test::errorOf([] { scpu::emulatedPreset("fp32-nr"); }).find("Newton-Raphson"), std::string::npos);
  EXPECT_NE(test::errorOf([] { scpu::emulatedPreset("fp32-rsqrt-dr"); }).find("rsqrt"), std::string::npos);
  const auto unknown = test::errorOf([] { scpu::emulatedPreset("fp12"); });
  EXPECT_NE(unknown.find("'fp12'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("fp16-robust"), std::string::npos) << unknown;  // names what it has
  EXPECT_EQ(backendNameError("model:fp16"), "");
  EXPECT_NE(backendNameError("model:fp32-nr").find("Newton-Raphson"), std::string::npos);
  EXPECT_NE(backendNameError("modle:fp16").find("model:<preset>"), std::string::npos);
  BackendRequest request;
  request.name = "model:fp12";
  EXPECT_THROW(makeBackend(request), std::invalid_argument);
  request.name = "model:bf16";
  EXPECT_EQ(makeBackend(request)->name(), "model:bf16");
}

TEST(ScpuModelCpp, ValuesOutsideTheLinkFormatAreFlaggedNotDropped) {
  // binary16 tops out at 65504: a centre at 1e5 becomes infinite on the link, a radius of
  // 1e-9 becomes zero. Both pairs are flagged REC_HOST_RANGE; the good pair is untouched.
  SphereTable s;
  s.push(0, 0, 0, 0.5);
  s.push(0.6, 0, 0, 0.5);
  s.push(1e5, 0, 0, 0.5);
  s.push(0.1, 0, 0, 1e-9);
  PairList p;
  p.push(0, 1);
  p.push(0, 2);
  p.push(0, 3);
  ModelBackend b("fp16");
  ContactSet out;
  collidePairs(b, s, p, out);
  EXPECT_EQ(b.format(), LinkFormat::Binary16);
  EXPECT_EQ(out.hit[0], 1);
  EXPECT_EQ(out.flags[0] & contract::REC_HOST_RANGE, 0u);
  EXPECT_NE(out.flags[1] & contract::REC_HOST_RANGE, 0u);
  EXPECT_NE(out.flags[2] & contract::REC_HOST_RANGE, 0u);
}

TEST(ScpuModelCpp, APairNamingASphereOutsideTheTableIsAnErrorNamingIt) {
  SphereTable s;
  s.push(0, 0, 0, 1);
  s.push(1, 0, 0, 1);
  PairList p;
  p.push(0, 1);
  p.push(1, 2);
  ModelBackend b("fp32");
  ContactSet out;
  EXPECT_EQ(test::errorOf([&] { b.collide(s, p, out); }), "backend model:fp32: pair 1 names sphere 2 of a table of 2");
}
