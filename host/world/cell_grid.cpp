#include "world/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

namespace collide::world {

namespace {
constexpr int kDigitBits = 11;  // the radix sort's digit: 2048 counters stay in L1

// The binary32 decision of the simd kernel (collide/simd_kernel.cpp) for one sphere against n,
// vectorized like it (one copy an ISA, the same IEEE operations in each). It is symmetric in
// the two spheres: fl(a - b) = -fl(b - a), and the sums commute.
__attribute__((noinline, target_clones("avx512f", "avx2", "default")))
void decideN(std::size_t n, Ball a, const Ball* __restrict c, std::uint8_t* __restrict hit) {
  for (std::size_t k = 0; k < n; ++k) {
    const float dx = a.x - c[k].x, dy = a.y - c[k].y, dz = a.z - c[k].z;
    const float d = std::sqrt(dx * dx + dy * dy + dz * dz);
    hit[k] = !(d > a.r + c[k].r);
  }
}

int bitWidth(std::uint64_t v) {
  int b = 0;
  for (; v; v >>= 1) ++b;
  return b;
}
}  // namespace

// floor(c / h) without a libm call (x86-64's baseline has no rounding instruction): truncate,
// then step down where that rounded up. |c / h| < 2^62 (the cell edge is widened until so).
std::int64_t CellGrid::cellOfD(double c) const {
  const double v = c * inv_;
  const auto t = static_cast<std::int64_t>(v);
  return t - (v < static_cast<double>(t));
}
std::int64_t CellGrid::cellOf(float c) const { return cellOfD(static_cast<double>(c)); }

void CellGrid::build(const SpheresF32& s, const std::vector<std::uint32_t>& ids) {
  large_.clear();
  small_.clear();
  key_.clear();
  id_.clear();
  const std::size_t n = ids.size();
  rc_ = 0;
  h_ = 0x1p-10;
  inv_ = 1 / h_;
  if (n == 0) return;

  // The cut radius: all but max(16, n/16) spheres are small.
  const std::size_t rank = n <= 32 ? 0 : std::max<std::size_t>(16, n / kLargeShare);
  float most = s.r[ids[0]];
  std::size_t atMost = 0;
  for (auto id : ids) most = std::max(most, s.r[id]);
  for (auto id : ids) atMost += s.r[id] == most;
  if (atMost > rank) {
    rc_ = most;  // equal radii: no selection needed
  } else {
    radii_.resize(n);
    for (std::size_t k = 0; k < n; ++k) radii_[k] = s.r[ids[k]];
    std::nth_element(radii_.begin(), radii_.begin() + static_cast<std::ptrdiff_t>(rank), radii_.end(), std::greater<float>());
    rc_ = radii_[rank];
  }
  for (auto id : ids) (s.r[id] > rc_ ? large_ : small_).push_back(id);

  // The occupied range on each axis (the cell is monotone in the coordinate), and the cell
  // edge: the least that the rule allows, doubled while the key would not fit.
  float mn[3], mx[3];
  const float* axis[3] = {s.x, s.y, s.z};
  for (int a = 0; a < 3; ++a) mn[a] = mx[a] = axis[a][small_[0]];
  for (auto id : small_)
    for (int a = 0; a < 3; ++a) {
      mn[a] = std::min(mn[a], axis[a][id]);
      mx[a] = std::max(mx[a], axis[a][id]);
    }
  h_ = std::max(2.0 * rc_ * (1 + 0x1p-10), 0x1p-10);
  std::uint64_t dim[3];
  for (;;) {
    inv_ = 1 / h_;
    for (int a = 0; a < 3; ++a) {
      lo_[a] = cellOf(mn[a]);
      span_[a] = cellOf(mx[a]) - lo_[a];
      dim[a] = static_cast<std::uint64_t>(span_[a]) + 3;  // offsets 0 .. span + 2
    }
    if (static_cast<double>(dim[0]) * static_cast<double>(dim[1]) * static_cast<double>(dim[2]) < 0x1p62) break;
    h_ *= 2;
  }
  dimZ_ = dim[2];
  dimYZ_ = dim[1] * dim[2];
  cells_ = dim[0] * dimYZ_;
  rowOff_[0] = dimZ_ - 1;           // (x, y+1, z-1)
  rowOff_[1] = dimYZ_ - dimZ_ - 1;  // (x+1, y-1, z-1)
  rowOff_[2] = dimYZ_ - 1;          // (x+1, y, z-1)
  rowOff_[3] = dimYZ_ + dimZ_ - 1;  // (x+1, y+1, z-1)

  const std::size_t m = small_.size();
  key_.resize(m);
  id_.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    const auto id = small_[k];
    key_[k] = keyOf(static_cast<std::uint64_t>(cellOf(s.x[id]) - lo_[0] + 1),
                    static_cast<std::uint64_t>(cellOf(s.y[id]) - lo_[1] + 1),
                    static_cast<std::uint64_t>(cellOf(s.z[id]) - lo_[2] + 1));
    id_[k] = id;
  }
  dense_ = cells_ <= kDenseCellsPerSphere * m + kDenseCellsAlways;
  if (dense_) countingSort();
  else radixSort(bitWidth(cells_));
  ball_.resize(m + kCopy);
  id_.resize(m + kCopy);
  for (std::size_t k = 0; k < m; ++k) {
    const auto id = id_[k];
    ball_[k] = {s.x[id], s.y[id], s.z[id], s.r[id]};
  }
}

// Stable LSD radix sort: within a key, the input (position) order stays.
void CellGrid::radixSort(int bits) {
  const std::size_t n = key_.size();
  keyTmp_.resize(n);
  idTmp_.resize(n);
  for (int shift = 0; shift < bits; shift += kDigitBits) {
    count_.assign((std::size_t{1} << kDigitBits) + 1, 0);
    const std::uint64_t mask = (std::uint64_t{1} << kDigitBits) - 1;
    for (std::size_t k = 0; k < n; ++k) ++count_[((key_[k] >> shift) & mask) + 1];
    for (std::size_t d = 1; d < count_.size(); ++d) count_[d] += count_[d - 1];
    for (std::size_t k = 0; k < n; ++k) {
      const auto to = count_[(key_[k] >> shift) & mask]++;
      keyTmp_[to] = key_[k];
      idTmp_[to] = id_[k];
    }
    key_.swap(keyTmp_);
    id_.swap(idTmp_);
  }
}

// One stable counting sort over every cell; start_ keeps where each cell begins, so the walk
// finds a neighbour's spheres with two loads.
void CellGrid::countingSort() {
  const std::size_t n = key_.size();
  start_.assign(cells_ + 1, 0);
  for (std::size_t k = 0; k < n; ++k) ++start_[key_[k] + 1];
  for (std::size_t c = 0; c < cells_; ++c) start_[c + 1] += start_[c];
  count_.assign(start_.begin(), start_.end() - 1);  // the scatter's cursors
  keyTmp_.resize(n);
  idTmp_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto to = count_[key_[k]]++;
    keyTmp_[to] = key_[k];
    idTmp_[to] = id_[k];
  }
  key_.swap(keyTmp_);
  id_.swap(idTmp_);
}

std::size_t CellGrid::cellStart(std::size_t p) const {
  while (p > 0 && p < key_.size() && key_[p] == key_[p - 1]) ++p;
  return std::min(p, key_.size());
}

std::size_t CellGrid::lowerBound(std::uint64_t k) const {
  return static_cast<std::size_t>(std::lower_bound(key_.begin(), key_.end(), k) - key_.begin());
}

// The binary32 decision of the simd kernel (collide/simd_kernel.cpp), which is symmetric in
// the two spheres: fl(a - b) = -fl(b - a), and the sums commute.
void CellGrid::testRange(const Probe& a, std::size_t q0, std::size_t q1, HitList& out) const {
  std::uint64_t* w = out.pairs.data() + out.count;
  std::size_t kept = 0;
  const std::uint64_t ida = a.id;
  for (std::size_t q = q0; q < q1; ++q) {
    const Ball& b = ball_[q];
    const float dx = a.b.x - b.x, dy = a.b.y - b.y, dz = a.b.z - b.z;
    const float d = std::sqrt(dx * dx + dy * dy + dz * dz);
    const bool hit = !(d > a.b.r + b.r);
    const std::uint64_t idb = id_[q];
    w[kept] = ida < idb ? (ida << 32 | idb) : (idb << 32 | ida);
    kept += hit;
  }
  out.count += kept;
  out.tested += q1 > q0 ? q1 - q0 : 0;
}

void CellGrid::test(const Probe& a, std::size_t q0, std::size_t q1, HitList& out) const {
  if (q1 <= q0) return;
  out.room(q1 - q0);
  testRange(a, q0, q1, out);
}

void CellGrid::walk(std::size_t p0, std::size_t p1, HitList& out) const {
  if (p0 >= p1 || p0 >= key_.size()) return;
  if (dense_) walkDense(p0, p1, out);
  else walkSparse(p0, p1, out);
}

// The cell at key K: [start_[K], start_[K+1]); its neighbours' rows likewise.
void CellGrid::walkDense(std::size_t p0, std::size_t p1, HitList& out) const {
  const std::uint64_t* key = key_.data();
  const std::uint32_t* start = start_.data();
  for (std::size_t a = p0; a < p1;) {
    const std::uint64_t K = key[a];
    const std::size_t b = start[K + 1], e = start[K + 2];
    Range rows[5] = {{0, e}};
    for (int r = 0; r < 4; ++r) rows[r + 1] = {start[K + rowOff_[r]], start[K + rowOff_[r] + 3]};
    testCell(a, b, rows, out);
    a = b;
  }
}

// Without a table of every cell: a pointer a row that only moves forward.
void CellGrid::walkSparse(std::size_t p0, std::size_t p1, HitList& out) const {
  const std::size_t n = key_.size();
  const std::uint64_t* key = key_.data();
  std::size_t lo[4], hi[4];
  for (int r = 0; r < 4; ++r) lo[r] = hi[r] = lowerBound(key[p0] + rowOff_[r]);
  std::size_t e = p0;  // the end of the cell at z + 1
  for (std::size_t a = p0; a < p1;) {
    const std::uint64_t K = key[a];
    std::size_t b = a + 1;
    while (b < n && key[b] == K) ++b;
    e = std::max(e, b);
    while (e < n && key[e] == K + 1) ++e;
    Range rows[5] = {{0, e}};
    for (int r = 0; r < 4; ++r) {
      const std::uint64_t S = K + rowOff_[r];
      while (lo[r] < n && key[lo[r]] < S) ++lo[r];
      hi[r] = std::max(hi[r], lo[r]);
      while (hi[r] < n && key[hi[r]] < S + 3) ++hi[r];
      rows[r + 1] = {lo[r], hi[r]};
    }
    testCell(a, b, rows, out);
    a = b;
  }
}

// The spheres [a, b) of one cell: each against the later ones up to rows[0].end (its own cell
// and the one at z + 1), then against rows 1-4. The candidates are gathered once for the cell,
// so each sphere is one vectorized loop over them rather than five short ones.
void CellGrid::testCell(std::size_t a, std::size_t b, const Range rows[5], HitList& out) const {
  std::size_t n = rows[0].end - a;
  for (int r = 1; r < 5; ++r) n += rows[r].end - rows[r].begin;
  if (out.cand.size() < n + kCopy) {
    out.cand.resize(2 * n + kCopy);
    out.cid.resize(2 * n + kCopy);
    out.hit.resize(2 * n + kCopy);
  }
  std::size_t k = 0;
  auto gather = [&](std::size_t q0, std::size_t q1) {
    const std::size_t len = q1 - q0;
    std::memcpy(&out.cand[k], &ball_[q0], kCopy * sizeof(Ball));
    std::memcpy(&out.cid[k], &id_[q0], kCopy * sizeof(std::uint32_t));
    if (len > kCopy) {
      std::memcpy(&out.cand[k + kCopy], &ball_[q0 + kCopy], (len - kCopy) * sizeof(Ball));
      std::memcpy(&out.cid[k + kCopy], &id_[q0 + kCopy], (len - kCopy) * sizeof(std::uint32_t));
    }
    k += len;
  };
  gather(a, rows[0].end);
  for (int r = 1; r < 5; ++r) gather(rows[r].begin, rows[r].end);
  out.room((b - a) * n);
  for (std::size_t p = a; p < b; ++p) {
    const std::size_t k0 = p - a + 1;  // the cell's later spheres on
    decideN(n - k0, ball_[p], out.cand.data() + k0, out.hit.data());
    std::uint64_t* w = out.pairs.data() + out.count;
    std::size_t kept = 0;
    const std::uint64_t ida = id_[p];
    for (std::size_t c = 0; c < n - k0; ++c) {
      const std::uint64_t idb = out.cid[k0 + c];
      w[kept] = ida < idb ? (ida << 32 | idb) : (idb << 32 | ida);
      kept += out.hit[c];
    }
    out.count += kept;
    out.tested += n - k0;
  }
}

void CellGrid::probe(const SpheresF32& s, std::uint32_t id, HitList& out) const {
  const std::size_t n = key_.size();
  if (n == 0) return;
  const Probe a{{s.x[id], s.y[id], s.z[id], s.r[id]}, id};
  // Binary32 calls a pair a hit only within (r1 + r2)(1 + 2^-21) on each axis.
  const double ext = (static_cast<double>(a.b.r) + rc_) * (1 + 0x1p-10) + 0x1p-20;
  const float c[3] = {a.b.x, a.b.y, a.b.z};
  std::int64_t l[3], h[3];
  for (int k = 0; k < 3; ++k) {
    l[k] = std::max<std::int64_t>(cellOfD(c[k] - ext) - lo_[k], 0) + 1;
    h[k] = std::min<std::int64_t>(cellOfD(c[k] + ext) - lo_[k], span_[k]) + 1;
    if (l[k] > h[k]) return;
  }
  const auto rows = static_cast<std::uint64_t>(h[0] - l[0] + 1) * static_cast<std::uint64_t>(h[1] - l[1] + 1);
  if (rows > n / 16 + 1) return test(a, 0, n, out);  // a scan is cheaper than the searches
  for (auto ux = l[0]; ux <= h[0]; ++ux)
    for (auto uy = l[1]; uy <= h[1]; ++uy) {
      const auto kx = static_cast<std::uint64_t>(ux), ky = static_cast<std::uint64_t>(uy);
      const std::uint64_t k0 = keyOf(kx, ky, static_cast<std::uint64_t>(l[2]));
      const std::uint64_t k1 = keyOf(kx, ky, static_cast<std::uint64_t>(h[2])) + 1;
      test(a, dense_ ? start_[k0] : lowerBound(k0), dense_ ? start_[k1] : lowerBound(k1), out);
    }
}

}  // namespace collide::world
