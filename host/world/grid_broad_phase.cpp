#include "world/grid_broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace collide::world {

namespace {
// The forward half shell: the 13 neighbour offsets lexicographically after (0, 0, 0). Of two
// neighbouring cells exactly one lies in the other's forward half shell.
constexpr std::array<std::array<std::int32_t, 3>, 13> kHalfShell = {{
    {0, 0, 1}, {0, 1, -1}, {0, 1, 0}, {0, 1, 1},
    {1, -1, -1}, {1, -1, 0}, {1, -1, 1}, {1, 0, -1}, {1, 0, 0}, {1, 0, 1}, {1, 1, -1}, {1, 1, 0}, {1, 1, 1}}};

bool sameCell(const std::array<std::int32_t, 3>& a, const std::array<std::int32_t, 3>& b) {
  return (a[0] == b[0]) & (a[1] == b[1]) & (a[2] == b[2]);
}
}  // namespace

double GridBroadPhase::ldexpExact(int k) { return std::ldexp(1.0, k); }

GridShape GridBroadPhase::chooseShape(const SphereTable& s, const std::vector<std::uint32_t>& members) {
  GridShape g;
  g.cellExp = kMinCellExp;
  if (members.empty()) return g;
  std::vector<double> r(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) r[k] = s.r[members[k]];
  // The (kMaxLarge+1)-th largest radius (the smallest if there are fewer): only the kMaxLarge
  // above it can be large.
  const std::size_t rank = std::min(kMaxLarge, r.size() - 1);
  std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(rank), r.end(), std::greater<>());
  g.smallRadiusMax = r[rank];
  // The least k with 2.5 r <= 2^k: frexp gives 2.5 r = m 2^e, m in [0.5, 1).
  int e = 0;
  const double m = std::frexp(2.5 * g.smallRadiusMax, &e);
  g.cellExp = std::max(kMinCellExp, m == 0.5 ? e - 1 : e);
  for (auto idx : members) g.large += isLarge(s.r[idx], g.cellExp);
  return g;
}

std::int32_t GridBroadPhase::cellOf(double c, int cellExp) {
  double t = std::floor(std::ldexp(c, -cellExp));  // exact while c / 2^k is a normal double
  // A negative c so tiny that c / 2^k underflowed to -0 lies in cell -1, not 0.
  if (c < 0 && t == 0) t = -1;
  return static_cast<std::int32_t>(t);
}

std::uint32_t GridBroadPhase::hashOf(const Cell& c, std::uint32_t shift) {
  // Mix the three coordinates (Teschner et al.'s primes), then keep the top bits of a
  // Fibonacci multiply, which depend on every bit of the mix.
  const std::uint32_t h = (static_cast<std::uint32_t>(c[0]) * 73856093u) ^ (static_cast<std::uint32_t>(c[1]) * 19349663u) ^
                          (static_cast<std::uint32_t>(c[2]) * 83492791u);
  return (h * 0x9E3779B1u) >> shift;
}

// Counts the pair among the cells' pairs, and keeps it if the grown boxes overlap.
void GridBroadPhase::consider(const Entry& a, const Entry& b, std::size_t& cellPairs, PairList& out) {
  ++cellPairs;
  if (!boxesOverlap(a.x - b.x, a.y - b.y, a.z - b.z, a.reach + b.reach)) return;
  out.push(std::min(a.index, b.index), std::max(a.index, b.index));
}

GridBroadPhase::Entry GridBroadPhase::entryOf(const SphereTable& s, std::uint32_t i, const Cell& cell) {
  return Entry{cell, i, s.x[i], s.y[i], s.z[i], reachOf(s.r[i])};
}


void GridBroadPhase::findPairs(const SphereTable& s, const std::vector<std::uint32_t>& members, PairList& out) {
  shape_ = chooseShape(s, members);
  const int k = shape_.cellExp;
  small_.clear();
  large_.clear();
  for (auto idx : members) (isLarge(s.r[idx], k) ? large_ : small_).push_back(idx);

  // Counting sort of the small spheres by bucket: count, prefix sum, scatter in index order.
  const std::size_t n = small_.size();
  std::uint32_t bits = 1;
  while ((std::size_t{1} << bits) < 2 * n) ++bits;
  shape_.buckets = std::size_t{1} << bits;
  const std::uint32_t shift = 32 - bits;
  cell_.resize(n);
  bucket_.resize(n);
  start_.assign(shape_.buckets + 1, 0);
  for (std::size_t e = 0; e < n; ++e) {
    const auto i = small_[e];
    cell_[e] = {cellOf(s.x[i], k), cellOf(s.y[i], k), cellOf(s.z[i], k)};
    bucket_[e] = hashOf(cell_[e], shift);
    ++start_[bucket_[e] + 1];
  }
  for (std::size_t b = 0; b < shape_.buckets; ++b) start_[b + 1] += start_[b];
  cursor_.assign(start_.begin(), start_.end() - 1);
  sorted_.resize(n);
  for (std::size_t e = 0; e < n; ++e) {
    sorted_[cursor_[bucket_[e]]++] = entryOf(s, small_[e], cell_[e]);
  }

  // Each small sphere: its own cell (higher indices only), then the forward half shell. The
  // walks are branch-free: whether a pair is kept is data-dependent and unpredictable, so
  // every entry is written and the count advances only for a kept one.
  std::size_t cellPairs = 0, kept = 0;
  auto walk = [&](const Entry& a, std::uint32_t bucket, const Cell& c, bool ownCell) {
    const auto q0 = start_[bucket], q1 = start_[bucket + 1];
    if (kept + (q1 - q0) > keptI_.size()) {
      keptI_.resize(std::max(2 * keptI_.size(), kept + (q1 - q0) + 1024));
      keptJ_.resize(keptI_.size());
    }
    for (auto q = q0; q < q1; ++q) {
      const Entry& b = sorted_[q];
      const bool pair = sameCell(b.cell, c) & (!ownCell | (b.index > a.index));
      cellPairs += pair;
      keptI_[kept] = std::min(a.index, b.index);
      keptJ_[kept] = std::max(a.index, b.index);
      kept += pair & boxesOverlap(a.x - b.x, a.y - b.y, a.z - b.z, a.reach + b.reach);
    }
  };
  for (std::size_t p = 0; p < n; ++p) {
    const Entry& a = sorted_[p];
    walk(a, hashOf(a.cell, shift), a.cell, true);
    for (const auto& d : kHalfShell) {
      const Cell c = {a.cell[0] + d[0], a.cell[1] + d[1], a.cell[2] + d[2]};  // |cell| <= 2^30: no overflow
      walk(a, hashOf(c, shift), c, false);
    }
  }
  out.i.insert(out.i.end(), keptI_.begin(), keptI_.begin() + static_cast<std::ptrdiff_t>(kept));
  out.j.insert(out.j.end(), keptJ_.begin(), keptJ_.begin() + static_cast<std::ptrdiff_t>(kept));

  // Large spheres against everything else, each pair once (few: branches are fine here).
  for (std::size_t a = 0; a < large_.size(); ++a) {
    const Entry la = entryOf(s, large_[a]);
    for (const Entry& b : sorted_) consider(la, b, cellPairs, out);
    for (std::size_t b = a + 1; b < large_.size(); ++b) consider(la, entryOf(s, large_[b]), cellPairs, out);
  }
  shape_.cellPairs = cellPairs;
}

}  // namespace collide::world
