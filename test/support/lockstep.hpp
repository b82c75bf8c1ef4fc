#pragma once
// Two simulations of one scene side by side, each with its own collision backend, compared
// after every step: the hit sets (as sphere index pairs) and the sphere positions. Hits that
// only one side has are split into "grazing" (|d - (r1 + r2)| <= grazingTol, computed in
// binary64 from that side's sphere table: a binary32 and a binary64 collider may rightly
// disagree there) and real disagreements.
//
// ODE's quickstep reorders constraints with its global random generator (dRandInt), so
// two worlds stepped in turn would disturb each other: each side keeps its own seed.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "collide/backend.hpp"
#include "scene/scene.hpp"
#include "simulation/simulation.hpp"

namespace collide::test {

struct LockstepStep {
  std::size_t pairsA = 0, pairsB = 0, hitsA = 0, hitsB = 0;
  std::size_t onlyA = 0, onlyB = 0;                // hits one side has and the other not
  std::size_t onlyAGrazing = 0, onlyBGrazing = 0;  // of those, within the grazing tolerance
  double maxGrazingGap = 0;                        // largest |d - (r1 + r2)| among "only" hits
  double maxPosDiff = 0;                           // after the step, max over spheres and axes
};

inline std::vector<LockstepStep> lockstep(const scene::Scene& sc, CollisionBackend& a, CollisionBackend& b,
                                          long long steps, double grazingTol) {
  using Hits = std::set<std::pair<std::uint32_t, std::uint32_t>>;
  struct Side {
    Hits hits;
    SphereTable table;
    std::size_t pairs = 0;
  } sa, sb;
  auto observe = [](Side& s) {
    return [&s](const SphereTable& t, const PairList& p, const ContactSet& c) {
      s.hits.clear();
      s.table = t;
      s.pairs = p.size();
      for (std::size_t k = 0; k < p.size(); ++k)
        if (c.hit[k]) s.hits.insert(std::minmax(p.i[k], p.j[k]));
    };
  };
  sim::Simulation simA(sc, a), simB(sc, b);
  simA.setBatchObserver(observe(sa));
  simB.setBatchObserver(observe(sb));
  std::vector<LockstepStep> out;
  unsigned long seedA = dRandGetSeed(), seedB = seedA;
  for (long long s = 0; s < steps; ++s) {
    dRandSetSeed(seedA);
    simA.step();
    seedA = dRandGetSeed();
    dRandSetSeed(seedB);
    simB.step();
    seedB = dRandGetSeed();
    LockstepStep st;
    st.pairsA = sa.pairs;
    st.pairsB = sb.pairs;
    st.hitsA = sa.hits.size();
    st.hitsB = sb.hits.size();
    auto only = [&](const Side& x, const Side& y, std::size_t& n, std::size_t& grazing) {
      for (const auto& [i, j] : x.hits) {
        if (y.hits.count({i, j})) continue;
        ++n;
        const double dx = x.table.x[i] - x.table.x[j], dy = x.table.y[i] - x.table.y[j],
                     dz = x.table.z[i] - x.table.z[j];
        const double gap = std::fabs(std::sqrt(dx * dx + dy * dy + dz * dz) - (x.table.r[i] + x.table.r[j]));
        st.maxGrazingGap = std::max(st.maxGrazingGap, gap);
        grazing += gap <= grazingTol;
      }
    };
    only(sa, sb, st.onlyA, st.onlyAGrazing);
    only(sb, sa, st.onlyB, st.onlyBGrazing);
    for (std::size_t k = 0; k < simA.world().sphereCount(); ++k) {
      const dReal* pa = dBodyGetPosition(simA.world().sphereBody(k));
      const dReal* pb = dBodyGetPosition(simB.world().sphereBody(k));
      for (int c = 0; c < 3; ++c) st.maxPosDiff = std::max(st.maxPosDiff, std::fabs(pa[c] - pb[c]));
    }
    out.push_back(st);
  }
  return out;
}

}  // namespace collide::test
