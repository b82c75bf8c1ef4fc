#include "world/tuned_world.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <string>
#include <utility>

#include "afu_contract.hpp"
#include "collide/simd_kernel.hpp"

namespace collide::world {

namespace {
using Clock = std::chrono::steady_clock;
std::int64_t nsSince(Clock::time_point t0) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t0).count();
}
// Thread t's share [first, second) of n items among `of` threads.
std::pair<std::size_t, std::size_t> slice(std::size_t n, unsigned t, unsigned of) {
  return {n * t / of, n * (t + 1) / of};
}
}  // namespace

TunedWorld::TunedWorld(unsigned threads) : team_(std::max(1u, threads)), hits_(team_.size()) {}

std::string TunedWorld::name() const {
  return "grid (tuned, " + std::to_string(threads()) + (threads() == 1 ? " thread)" : " threads)");
}

void TunedWorld::collide(const SphereTable& s, WorldContacts& out, WorldTiming& time) {
  // Emptied, not freed: a repeated collision (a simulation's steps, --repeat) writes into the
  // same memory.
  out.pairs.clear();
  out.badSpheres.clear();
  out.badFlags.clear();
  out.candidates = out.flaggedMisses = 0;
  out.contacts.format = LinkFormat::Binary32;
  time = WorldTiming{};
  splitSpheres(s, out, members_);  // untimed, as in WorldCollider

  auto t0 = Clock::now();
  const std::size_t m = members_.size();
  x_.resize(m);
  y_.resize(m);
  z_.resize(m);
  r_.resize(m);
  team_.run([&](unsigned t) {
    const auto [a, b] = slice(m, t, team_.size());
    for (std::size_t k = a; k < b; ++k) {
      const auto i = members_[k];
      x_[k] = static_cast<float>(s.x[i]);
      y_[k] = static_cast<float>(s.y[i]);
      z_[k] = static_cast<float>(s.z[i]);
      r_[k] = static_cast<float>(s.r[i]);
    }
  });
  const SpheresF32 f{x_.data(), y_.data(), z_.data(), r_.data()};
  for (auto& h : hits_) h.clear();
  levels_.clear();
  ids_.resize(m);
  std::iota(ids_.begin(), ids_.end(), 0u);
  for (std::size_t level = 0; !ids_.empty(); ++level) {
    if (grids_.size() <= level) grids_.push_back(std::make_unique<CellGrid>());
    CellGrid& g = *grids_[level];
    g.build(f, ids_);
    levels_.push_back({ids_.size(), g.large().size(), g.cellEdge()});
    walkLevel(g, f);
    ids_ = g.large();
  }
  time.broadNs = nsSince(t0);
  for (const auto& h : hits_) out.candidates += h.tested;

  t0 = Clock::now();
  orderHits(out);
  time.finishNs = nsSince(t0);

  t0 = Clock::now();
  writeContacts(s, out);
  time.narrowNs = nsSince(t0);
}

void TunedWorld::walkLevel(const CellGrid& g, const SpheresF32& f) {
  const std::size_t n = g.smallCount(), chunks = (n + kChunk - 1) / kChunk;
  const std::size_t jobs = chunks + g.large().size();
  next_ = 0;
  team_.run([&](unsigned t) {
    HitList& h = hits_[t];
    for (std::size_t c; (c = next_.fetch_add(1, std::memory_order_relaxed)) < jobs;) {
      if (c < chunks) g.walk(g.cellStart(c * kChunk), g.cellStart(std::min(n, (c + 1) * kChunk)), h);
      else g.probe(f, g.large()[c - chunks], h);
    }
  });
}

// A counting sort of every thread's hits by i, then each i's j by insertion (a sphere has a
// handful of contacts; std::sort for more): O(members + contacts), and the order is the
// pairs' alone.
void TunedWorld::orderHits(WorldContacts& out) {
  const std::size_t m = members_.size();
  start_.assign(m + 1, 0);
  for (const auto& h : hits_)
    for (std::size_t k = 0; k < h.count; ++k) ++start_[(h.pairs[k] >> 32) + 1];
  for (std::size_t i = 0; i < m; ++i) start_[i + 1] += start_[i];
  const std::size_t total = start_[m];
  cursor_.assign(start_.begin(), start_.end() - 1);
  pj_.resize(total);
  for (const auto& h : hits_)
    for (std::size_t k = 0; k < h.count; ++k)
      pj_[cursor_[h.pairs[k] >> 32]++] = static_cast<std::uint32_t>(h.pairs[k]);
  out.pairs.i.resize(total);
  out.pairs.j.resize(total);
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t a = start_[i], b = start_[i + 1];
    if (b - a > 16) {  // a large sphere's many contacts
      std::sort(pj_.begin() + static_cast<std::ptrdiff_t>(a), pj_.begin() + static_cast<std::ptrdiff_t>(b));
    } else {
      for (std::size_t k = a + 1; k < b; ++k)
        for (std::size_t q = k; q > a && pj_[q - 1] > pj_[q]; --q) std::swap(pj_[q - 1], pj_[q]);
    }
    for (std::size_t k = a; k < b; ++k) {
      out.pairs.i[k] = members_[i];
      out.pairs.j[k] = members_[pj_[k]];
    }
  }
}

void TunedWorld::writeContacts(const SphereTable& s, WorldContacts& out) {
  ContactSet& c = out.contacts;
  const std::size_t n = out.pairs.size();
  c.resizeForOverwrite(n);
  const SpheresF64 table{s.x.data(), s.y.data(), s.z.data(), s.r.data()};
  constexpr auto kContact = static_cast<std::uint8_t>(contract::REC_HIT | contract::KIND_CONTACT << contract::REC_KIND_SHIFT);
  constexpr auto kCoincident = static_cast<std::uint8_t>(contract::REC_HIT | contract::KIND_COINCIDENT << contract::REC_KIND_SHIFT);
  team_.run([&](unsigned t) {
    const auto [a, b] = slice(n, t, team_.size());
    if (a == b) return;
    gatherCollideF32(b - a, table, out.pairs.i.data() + a, out.pairs.j.data() + a,
                     {c.px.data() + a, c.py.data() + a, c.pz.data() + a, c.nx.data() + a, c.ny.data() + a,
                      c.nz.data() + a, c.depth.data() + a, c.hit.data() + a});
    // The record flags as setCpuRecordFlags gives them to a hit of good spheres: coincident
    // where d^2 = (dx*dx + dy*dy) + dz*dz is zero in binary32.
    for (std::size_t k = a; k < b; ++k) {
      const auto i = out.pairs.i[k], j = out.pairs.j[k];
      const float dx = static_cast<float>(s.x[i]) - static_cast<float>(s.x[j]);
      const float dy = static_cast<float>(s.y[i]) - static_cast<float>(s.y[j]);
      const float dz = static_cast<float>(s.z[i]) - static_cast<float>(s.z[j]);
      c.flags[k] = (dx * dx + dy * dy) + dz * dz == 0 ? kCoincident : kContact;
    }
  });
}

}  // namespace collide::world
