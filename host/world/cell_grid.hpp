#pragma once
// One level of the tuned grid (world/tuned_world.hpp): the spheres of a level sorted by cell,
// and the walks that test every pair that can touch in binary32 exactly once.
//
// Spheres are the binary32 values the simd kernel sees (one RNE rounding of the table), by
// member position m (positions ascend with the table's index, so (min, max) positions order
// pairs as the table's (i, j) do). A level of spheres:
//  - the cut radius rc: the (max(16, n/16)+1)-th largest radius (the largest for n <= 32);
//    spheres with r > rc are "large" and go to the next level, the rest are "small";
//  - cells of edge h = max(2 rc (1 + 2^-10), 2^-10), doubled while the occupied cells number
//    2^62 or more; cell floor(c * (1/h)) per axis in binary64, which is monotone in c. Two
//    small spheres whose cells differ by 2 on an axis are more than h (1 - 2^-21) >
//    2 rc (1 + 2^-11) apart on it (|c| <= 1e6 m and h >= 2^-10 m keep the products' rounding
//    below 2^-22 of a cell), and binary32 calls a pair a hit only if its centres are at most
//    (r1 + r2)(1 + 2^-21) apart: such a pair is never a contact;
//  - the key of cell (x, y, z) is mixed-radix over the occupied box, each offset from the
//    least occupied cell plus one: keys order cells lexicographically, and a neighbour's key
//    is the key plus a constant;
//  - the small spheres in key order, each cell's in position order: with at most
//    kDenseCellsPerSphere cells a sphere, one counting sort whose table of cell starts stays
//    for the walk; otherwise an LSD radix sort (11-bit digits, stable).
// The walk visits cells in key order: each cell's spheres against the later spheres of the
// cell and of the cell at z + 1 (one contiguous range), and the four rows of three cells
// (x, y+1, z-1..z+1), (x+1, y-1..y+1, z-1..z+1): the forward half of the 26 neighbours. A row
// is two loads from the table of cell starts, or without one a pointer that only moves
// forward. The candidates of a cell are gathered once, and each of its spheres is one
// vectorized loop over them (the simd kernel's binary32 decision). A large sphere is tested
// against the small spheres of the cells its reach covers, row by row, or all of them when
// there are more rows than n / 16; large against large is the next level's business.
#include <cstdint>
#include <vector>

namespace collide::world {

// The members' binary32 values, by member position.
struct SpheresF32 {
  const float *x, *y, *z, *r;
};

// A sphere's binary32 values, 16 bytes: a candidate is one load.
struct Ball {
  float x, y, z, r;
};

// One thread's output and scratch. Hits as (min position << 32 | max position), written ahead
// and kept by count: the decision is data-dependent and unpredictable, so nothing branches on
// it.
struct HitList {
  std::vector<std::uint64_t> pairs;
  std::size_t count = 0;
  std::size_t tested = 0;  // pairs tested (the candidates)
  // A cell's candidates gathered contiguous, and one sphere's decisions on them.
  std::vector<Ball> cand;
  std::vector<std::uint32_t> cid;
  std::vector<std::uint8_t> hit;
  void clear() { count = tested = 0; }
  void room(std::size_t more) {
    if (count + more > pairs.size()) pairs.resize(2 * pairs.size() + more + 4096);
  }
};

class CellGrid {
 public:
  // At most this many cells a sphere (plus kDenseCellsAlways: a 256 KiB table costs nothing),
  // a table of every cell's start: one counting sort, and two loads find a neighbour row
  // (uniform worlds: 3-4 cells a sphere). Sparser worlds are radix sorted and searched.
  static constexpr std::size_t kDenseCellsPerSphere = 8;
  static constexpr std::size_t kDenseCellsAlways = 65536;
  // All but max(16, n / kLargeShare) spheres of a level are small. Measured on log-uniform
  // radii 0.2-0.8 (bench/results/grid): 16 and 64 alike, 2-8 slower (each level's probes).
  static constexpr std::size_t kLargeShare = 16;
  // Builds the level of `ids` (member positions, ascending); large() gets the large ones.
  void build(const SpheresF32& s, const std::vector<std::uint32_t>& ids);
  std::size_t smallCount() const { return key_.size(); }
  const std::vector<std::uint32_t>& large() const { return large_; }
  double cellEdge() const { return h_; }
  float cutRadius() const { return rc_; }
  // The first sorted place at or after p where a cell starts (smallCount() at the end).
  std::size_t cellStart(std::size_t p) const;
  // Every pair of small spheres whose first cell starts in [p0, p1) (cell starts), once.
  void walk(std::size_t p0, std::size_t p1, HitList& out) const;
  // Large sphere `id` (a member position) against every small sphere within its reach.
  void probe(const SpheresF32& s, std::uint32_t id, HitList& out) const;

 private:
  // Ranges of up to kCopy sorted places are copied whole (the arrays are padded so): the copy
  // does not depend on the range's length, so it costs no mispredicted branch.
  static constexpr std::size_t kCopy = 8;
  struct Probe {
    Ball b;
    std::uint32_t id;
  };
  std::int64_t cellOf(float c) const;
  std::int64_t cellOfD(double c) const;
  std::uint64_t keyOf(std::uint64_t ux, std::uint64_t uy, std::uint64_t uz) const { return ux * dimYZ_ + uy * dimZ_ + uz; }
  std::size_t lowerBound(std::uint64_t k) const;
  struct Range {
    std::size_t begin, end;
  };
  void walkDense(std::size_t p0, std::size_t p1, HitList& out) const;
  void walkSparse(std::size_t p0, std::size_t p1, HitList& out) const;
  void testCell(std::size_t a, std::size_t b, const Range rows[5], HitList& out) const;
  void test(const Probe& a, std::size_t q0, std::size_t q1, HitList& out) const;
  void testRange(const Probe& a, std::size_t q0, std::size_t q1, HitList& out) const;  // room made
  void radixSort(int bits);
  void countingSort();

  float rc_ = 0;
  double h_ = 0, inv_ = 0;
  std::int64_t lo_[3] = {0, 0, 0}, span_[3] = {0, 0, 0};  // least occupied cell, max - min
  std::uint64_t dimZ_ = 0, dimYZ_ = 0, cells_ = 0;  // keys: x * dimYZ + y * dimZ + z
  std::uint64_t rowOff_[4] = {0, 0, 0, 0};  // key of (x, y+1, z-1), (x+1, y-1..y+1, z-1) minus key of (x, y, z)
  bool dense_ = false;                      // start_ holds every cell's first place
  std::vector<std::uint32_t> large_, small_;
  std::vector<float> radii_;
  std::vector<std::uint64_t> key_, keyTmp_;
  std::vector<std::uint32_t> id_, idTmp_;
  std::vector<std::uint32_t> count_, start_;
  std::vector<Ball> ball_;  // the small spheres in key order (id_ beside), then kCopy padding
};

}  // namespace collide::world
