// The generated AFU compiled into this build (COLLIDE_AFU_PRESET / COLLIDE_AFU_DIR),
// Verilated, through the driver and link model. Registered only when a preset is built; also
// compiled against the cosim preset (collide_afu_cosim_tests), whose SCPUs are the C++ model.
//   - golden vectors from the Scala golden model (test/vectors/...), bit for bit;
//   - idle-cycle skipping: identical results and modelled time to stepping every cycle;
//   - the diamond: rtl against ode (contact sets up to grazing pairs, positions within a
//     tolerance) and, for an IEEE binary32 preset, against simd (identical).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "collide/model_backend.hpp"
#include "collide/ode_backend.hpp"
#include "collide/rtl_backend.hpp"
#include "collide/simd_backend.hpp"
#include "driver/afu_driver.hpp"
#include "driver/afu_factory.hpp"
#include "driver/manifest.hpp"
#include "collide/input_policy.hpp"
#include "support/bad_pairs.hpp"
#include "support/domain_pairs.hpp"
#include "support/golden_vectors.hpp"
#include "support/lockstep.hpp"
#include "support/random_batch.hpp"
#include "support/test_seed.hpp"

using namespace collide;
using namespace collide::driver;

namespace collide::test {
// The same stated tolerances as test_lockstep.cpp (simd vs ode).
constexpr long long kDiamondSteps = 6;
constexpr double kGrazingTol = 1e-6;
constexpr double kDiamondPosTol = 0.005;
}  // namespace collide::test

namespace {

Manifest builtIn() { return afuManifest(""); }

DriverOptions options(bool dense = false) {
  DriverOptions o;
  o.dense = dense;
  return withManifest(o, builtIn());
}

bool sameValue(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

std::string vectorsFile() {
  const std::string preset = builtInAfuPreset();
  // cosim is the default AFU with its SCPUs as the C++ model: the same SCPU, the same vectors.
  const std::string name = preset == "default" || preset == "cosim" ? "fp32_default.csv" : preset + ".csv";
  return std::string(COLLIDE_TEST_VECTORS) + "/" + name;
}

}  // namespace

TEST(Afu, MatchesTheGoldenModelVectorsBitForBit) {
  const std::string file = vectorsFile();
  if (!std::filesystem::exists(file))
    GTEST_SKIP() << "no golden vectors at " << file << " (the Scala golden model writes them; see docs/host.md)";
  const auto m = builtIn();
  const auto g = test::readGoldenVectors(file, m.format);
  ASSERT_GT(g.pairs.size(), 0u) << file << ": no rows";
  for (bool dense : {false, true}) {
    RtlBackend rtl(makeAfuPort({}, {}), link::LinkParams::ideal(), options(dense));
    ContactSet out;
    rtl.collide(g.spheres, g.pairs, out);
    std::size_t bad = 0;
    for (std::size_t k = 0; k < g.pairs.size() && bad < 20; ++k) {
      const auto& e = g.expected[k];
      const double got[7] = {out.px[k], out.py[k], out.pz[k], out.nx[k], out.ny[k], out.nz[k], out.depth[k]};
      bool ok = (out.hit[k] != 0) == e.hit;
      for (int c = 0; c < 7 && ok && e.hit; ++c) ok = sameValue(got[c], e.v[c]);
      if (!ok) {
        ++bad;
        ADD_FAILURE() << file << ":" << e.line << (dense ? " (dense)" : " (compact)") << ": hit " << int(out.hit[k])
                      << " want " << int(e.hit) << "; got " << std::hexfloat << got[0] << "," << got[1] << "," << got[2]
                      << " n " << got[3] << "," << got[4] << "," << got[5] << " depth " << got[6] << "; want "
                      << e.v[0] << "," << e.v[1] << "," << e.v[2] << " n " << e.v[3] << "," << e.v[4] << ","
                      << e.v[5] << " depth " << e.v[6] << std::defaultfloat;
      }
    }
    std::cout << "[ info     ] " << g.pairs.size() << " golden vectors, " << out.hits() << " contacts, "
              << rtl.lastBatch().runs << " AFU runs (" << (dense ? "dense" : "compact") << ")\n";
  }
}

TEST(Afu, SkippingIdleCyclesMatchesSteppingExactly) {
  const auto seed = test::testSeed(71);
  SphereTable t;
  PairList p;
  test::randomBatch(seed, 400, 3000, t, p, {2.0, 0.1, 0.5});
  auto lp = link::LinkParams::qpi();
  lp.seed = seed;
  for (bool dense : {false, true}) {
    DriverOptions skip = options(dense), step = options(dense);
    step.skipIdle = false;
    auto portA = makeAfuPort({}, {});
    auto portB = makeAfuPort({}, {});
    AfuDriver da(*portA, lp, skip), db(*portB, lp, step);
    const auto a = da.run(t, p);
    const auto b = db.run(t, p);
    EXPECT_EQ(std::memcmp(&a.status, &b.status, sizeof a.status), 0) << "status lines differ, dense " << dense;
    EXPECT_EQ(a.stats.statusCycle, b.stats.statusCycle);
    EXPECT_EQ(a.stats.modelledNs, b.stats.modelledNs);
    ASSERT_EQ(a.records.size(), b.records.size());
    for (std::size_t k = 0; k < a.records.size(); ++k) {
      EXPECT_EQ(a.records[k].pair, b.records[k].pair);
      EXPECT_EQ(a.records[k].flags, b.records[k].flags);
      const auto& ra = a.records[k];
      const auto& rb = b.records[k];
      for (auto [x, y] : {std::pair{ra.px, rb.px}, {ra.py, rb.py}, {ra.pz, rb.pz}, {ra.nx, rb.nx}, {ra.ny, rb.ny},
                          {ra.nz, rb.nz}, {ra.depth, rb.depth}})
        EXPECT_TRUE(sameValue(x, y)) << "record " << k;
    }
    EXPECT_EQ(b.stats.cyclesSkipped, 0u);
    if (portA->reportsIdle())
      EXPECT_GT(a.stats.cyclesSkipped, 0u) << "the AFU exports io_idle but no cycle was skipped";
    else
      std::cout << "[ info     ] nothing skipped: this AFU exposes no idle/busy port (docs/host.md); stepping is exact\n";
    std::cout << "[ info     ] " << (dense ? "dense" : "compact") << ": " << a.stats.statusCycle << " modelled cycles, "
              << a.stats.cyclesStepped << " stepped + " << a.stats.cyclesSkipped << " skipped (stepping all: "
              << b.stats.cyclesStepped << ")\n";
  }
}

TEST(AfuDiamond, RtlMatchesOdeUpToGrazingPairs) {
  auto sc = scene::loadScene(COLLIDE_REPO_SCENES "/diamond.json");
  RtlBackend rtl(std::filesystem::path{}, link::LinkParams::ideal(), options());
  OdeBackend ode;
  const auto r = test::lockstep(sc, rtl, ode, test::kDiamondSteps, test::kGrazingTol);
  for (std::size_t s = 0; s < r.size(); ++s) {
    EXPECT_EQ(r[s].pairsA, r[s].pairsB) << "step " << s;
    EXPECT_EQ(r[s].onlyA, r[s].onlyAGrazing) << "step " << s << ": rtl-only contacts that are not grazing";
    EXPECT_EQ(r[s].onlyB, r[s].onlyBGrazing) << "step " << s << ": ode-only contacts that are not grazing";
  }
  EXPECT_LT(r.back().maxPosDiff, test::kDiamondPosTol);
  std::size_t grazing = 0;
  for (const auto& x : r) grazing += x.onlyA + x.onlyB;
  std::cout << "[ info     ] " << grazing << " grazing disagreements, positions within " << r.back().maxPosDiff
            << " m after " << r.size() << " steps\n";
}

// IEEE binary32 with RNE and correctly rounded sqrt and divide computes ODE's dCollideSpheres
// formula (docs/scpu.md, "Semantics") exactly as the simd kernel does: same contacts, same trajectory, bit for bit.
TEST(AfuDiamond, Binary32RtlIsTheSimdColliderExactly) {
  if (builtIn().format != LinkFormat::Binary32) GTEST_SKIP() << "not a binary32 preset";
  if (builtIn().raw.value(nlohmann::json::json_pointer("/scpu/format/name"), std::string("fp32")) != "fp32")
    GTEST_SKIP() << "compute format is not fp32";
  auto sc = scene::loadScene(COLLIDE_REPO_SCENES "/diamond.json");
  RtlBackend rtl(std::filesystem::path{}, link::LinkParams::ideal(), options());
  SimdBackend simd;
  const auto r = test::lockstep(sc, rtl, simd, 20, 0.0);  // it flies apart by step 13
  for (std::size_t s = 0; s < r.size(); ++s) {
    EXPECT_EQ(r[s].onlyA + r[s].onlyB, 0u) << "step " << s;
    EXPECT_EQ(r[s].maxPosDiff, 0.0) << "step " << s;
  }
}


// The bad-pair policy (collide/input_policy.hpp) gives the AFU's results the decision and
// flags the CPU backends give: an infinite radius, which the SCPU calls a contact with NaN
// fields, is no contact here too; a pair outside a scene's range is computed and flagged;
// and every pair sent is still accounted for.
TEST(Afu, BadPairsGetTheDecisionAndFlagsOfTheCpuBackends) {
  if (builtIn().format != LinkFormat::Binary32) GTEST_SKIP() << "the cases are binary32 values";
  const auto b = test::badPairs();
  RtlBackend rtl(std::filesystem::path{}, link::LinkParams::ideal(), options());
  SimdBackend simd;
  ContactSet cr, cs;
  collidePairs(rtl, b.spheres, b.pairs, cr);
  collidePairs(simd, b.spheres, b.pairs, cs);
  ASSERT_EQ(cr.size(), b.pairs.size());
  for (std::size_t k = 0; k < b.pairs.size(); ++k) {
    EXPECT_EQ(cr.hit[k], cs.hit[k]) << "pair " << k << ": " << b.what[k];
    // The AFU alone sees its arithmetic's exceptions (REC_ARITH: the 6e19 m pair's square).
    EXPECT_EQ(cr.flags[k] & ~contract::REC_ARITH, cs.flags[k] & ~contract::REC_ARITH)
        << "pair " << k << ": " << b.what[k];
  }
}

// Vector mode over binary32's whole finite range on the AFU (docs/host.md, "Bad pairs"): pairs
// at 1e7, 1e30, 3e37 and subnormal scales are computed, never refused, and the AFU's records
// are the fp32 golden model's (model:fp32) bit for bit, values, kind and flags (REC_ARITH
// included), for an AFU whose SCPU that model reproduces.
TEST(Afu, VectorModeComputesEveryFiniteBinary32PairAsTheGoldenModel) {
  const auto m = builtIn();
  const auto& sc = m.raw.at("scpu");
  if (!(m.format == LinkFormat::Binary32 && sc.value("/format/name"_json_pointer, "") == "fp32" &&
        sc.value("distance", "") == "sqrt-recip" && sc.value("rounding", "") == "RNE" && sc.value("subnormals", false) &&
        sc.value("sqrtAlg", "") == "dr" && sc.value("recipAlg", "") == "dr"))
    GTEST_SKIP() << "model:fp32 reproduces an fp32 sqrt-recip SCPU with digit-recurrence roots; this AFU's is "
                 << sc.value("describe", "?");
  const std::uint64_t seed = test::testSeed(20261207);
  const auto d = test::domainPairs(seed, 100);
  RtlBackend rtl(std::filesystem::path{}, link::LinkParams::ideal(), options());
  ModelBackend model("fp32");
  ContactSet cr, cm;
  collidePairs(rtl, d.spheres, d.pairs, cr);
  collidePairs(model, d.spheres, d.pairs, cm);
  ASSERT_EQ(cr.size(), d.pairs.size());
  std::size_t hits = 0, arith = 0;
  for (std::size_t k = 0; k < d.pairs.size(); ++k) {
    const std::string what = "seed " + std::to_string(seed) + ", pair " + std::to_string(k) + " at scale " +
                             std::to_string(d.scale[k]);
    EXPECT_EQ(cr.hit[k], cm.hit[k]) << what;
    EXPECT_EQ(cr.flags[k], cm.flags[k]) << what;
    const std::vector<double>* a[] = {&cr.px, &cr.py, &cr.pz, &cr.nx, &cr.ny, &cr.nz, &cr.depth};
    const std::vector<double>* b[] = {&cm.px, &cm.py, &cm.pz, &cm.nx, &cm.ny, &cm.nz, &cm.depth};
    for (int f = 0; f < 7; ++f)
      EXPECT_EQ(std::memcmp(&(*a[f])[k], &(*b[f])[k], sizeof(double)), 0) << what << ", field " << f;
    hits += cr.hit[k];
    arith += (cr.flags[k] & contract::REC_ARITH) != 0;
  }
  EXPECT_GT(hits, 0u);
  EXPECT_GT(arith, 0u) << "some squares overflow binary32 at 3e37 m";
}

// Fault testing that moves: random batches through the real AFU over a hostile link (both
// request ports drop ready at random on 40 % of cycles, latencies 5..300 ns, responses
// reordered), compact and dense, seeded from the run seed: every pair is accounted for (the
// driver checks it) and the contacts are those of the ideal link, bit for bit.
TEST(Afu, AHostileLinkChangesTheTimeButNotOneContact) {
  const std::uint64_t seed = test::testSeed(20261201);
  std::mt19937_64 rng(seed);
  link::LinkParams hostile = link::LinkParams::qpi();
  hostile.readyDrop = 0.4;
  hostile.readLatencyMinNs = hostile.writeLatencyMinNs = 5;
  hostile.readLatencyMaxNs = hostile.writeLatencyMaxNs = 300;
  hostile.transactionOverheadNs = 0;
  std::uint64_t pairsRun = 0, slower = 0;
  for (int b = 0; b < 6; ++b) {
    SphereTable s;
    PairList p;
    test::randomBatch(rng(), 1 + rng() % 600, rng() % 700, s, p, {1.0, 0.05, 0.4});
    for (bool dense : {false, true}) {
      hostile.seed = rng();
      RtlBackend calm(std::filesystem::path{}, link::LinkParams::ideal(), options(dense));
      RtlBackend rough(std::filesystem::path{}, hostile, options(dense));
      ContactSet a, c;
      calm.collide(s, p, a);
      rough.collide(s, p, c);
      ASSERT_EQ(a.size(), c.size());
      for (std::size_t k = 0; k < a.size(); ++k) {
        ASSERT_EQ(a.hit[k], c.hit[k]) << "batch " << b << " pair " << k;
        ASSERT_EQ(a.flags[k], c.flags[k]) << "batch " << b << " pair " << k;
        using Col = std::vector<double> ContactSet::*;
        for (Col col : {&ContactSet::px, &ContactSet::py, &ContactSet::pz, &ContactSet::nx, &ContactSet::ny,
                        &ContactSet::nz, &ContactSet::depth})
          ASSERT_TRUE(sameValue((a.*col)[k], (c.*col)[k])) << "batch " << b << " pair " << k;
      }
      pairsRun += p.size();
      slower += rough.lastBatch().counters.cyclesTotal > calm.lastBatch().counters.cyclesTotal;
    }
  }
  std::cout << "[ info     ] " << pairsRun << " pairs over the hostile link, all contacts as on the ideal link\n";
  EXPECT_GT(slower, 0u) << "the hostile link never cost a cycle: is it hostile?";
}
