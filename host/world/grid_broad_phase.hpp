#pragma once
// The CPU broad phase of world mode: a uniform grid filled by a counting sort. The AFU's
// on-chip broad phase is to use the same rules (docs/host.md, "The grid broad phase"), so
// they are kept exact and small:
//  - cell size 2^k with 2^k >= 2.5 r for every "small" sphere (2r and a margin of 1/4, which
//    covers the narrow phase's rounding in any link format); k is the least such exponent for
//    the (kMaxLarge+1)-th largest radius, at least kMinCellExp;
//  - a sphere's cell is floor(c / 2^k) per axis, exact (a power-of-two scaling, then floor);
//  - small spheres are hashed by cell into a power-of-two bucket table of at least 2n buckets,
//    filled by a counting sort (count, prefix sum, scatter, in index order);
//  - each small sphere visits its own cell (pairing with higher indices) and the 13 cells of
//    the forward half shell (pairing with everything), taking only the spheres whose cell
//    equals the visited one, so a hash collision never yields a pair, nor a pair twice;
//  - "large" spheres (2.5 r > 2^k; at most kMaxLarge) pair with every other sphere;
//  - a pair found so is a candidate if on every axis |ci - cj| <= reach(i) + reach(j), with
//    reach(r) = 1.25 r + 2^-11 (the spheres' boxes grown by the same quarter, plus half the
//    least cell each for an underflowing distance), in binary64.
// Every pair comes out once, as (min, max). A small pair whose cells are not neighbours has
// |dc| > 2^k >= 2.5 max(r), which no narrow phase calls a hit; neither does it a pair whose
// grown boxes are apart.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "world/broad_phase.hpp"

namespace collide::world {

struct GridShape {
  int cellExp = 0;             // k: cells are 2^k wide
  double smallRadiusMax = 0;   // the radius k was chosen for
  std::size_t large = 0;       // spheres with 2.5 r > 2^k
  std::size_t buckets = 0;     // hash table size (a power of two)
  std::size_t cellPairs = 0;   // pairs in neighbouring cells or with a large sphere, before the box test
};

class GridBroadPhase final : public BroadPhase {
 public:
  static constexpr std::size_t kMaxLarge = 16;
  // 2^-10 m: with |c| <= 1e6 m (batch/sane_ranges.hpp) every cell index fits an int32
  // (1e6 * 2^10 < 2^31), and it covers the absolute error of an underflowing distance.
  static constexpr int kMinCellExp = -10;

  // The cell exponent for these radii (the rule above).
  static GridShape chooseShape(const SphereTable& s, const std::vector<std::uint32_t>& members);
  // Whether a sphere of radius r is large for cells 2^k wide.
  static bool isLarge(double r, int cellExp) { return 2.5 * r > ldexpExact(cellExp); }
  // floor(c / 2^k), exact.
  static std::int32_t cellOf(double c, int cellExp);
  // The box test's half-width of a sphere, and the test on the centres' differences.
  static double reachOf(double r) { return 1.25 * r + 0x1p-11; }
  static bool boxesOverlap(double dx, double dy, double dz, double reach) {
    return (std::fabs(dx) <= reach) & (std::fabs(dy) <= reach) & (std::fabs(dz) <= reach);
  }

  std::string name() const override { return "grid"; }
  void prepare(const SphereTable&, const std::vector<std::uint32_t>&) override {}
  // Candidate pairs among `members` (indices into s, each once), appended to `out` as
  // (min, max). Buffers are kept between calls.
  void findPairs(const SphereTable& s, const std::vector<std::uint32_t>& members, PairList& out) override;
  const GridShape& lastShape() const { return shape_; }

 private:
  static double ldexpExact(int k);
  using Cell = std::array<std::int32_t, 3>;
  // A small sphere as the bucket walks read it, contiguous.
  struct Entry {
    Cell cell;
    std::uint32_t index;
    double x, y, z, reach;
  };
  static std::uint32_t hashOf(const Cell& c, std::uint32_t shift);  // bucket: the top bits
  static Entry entryOf(const SphereTable& s, std::uint32_t i, const Cell& cell = {0, 0, 0});
  static void consider(const Entry& a, const Entry& b, std::size_t& cellPairs, PairList& out);

  GridShape shape_;
  std::vector<std::uint32_t> small_, large_;  // sphere indices
  std::vector<Cell> cell_;                    // cell of small_[e]
  std::vector<std::uint32_t> bucket_;         // bucket of small_[e]
  std::vector<std::uint32_t> start_;          // bucket b holds sorted positions start_[b] .. start_[b+1]-1
  std::vector<std::uint32_t> cursor_;         // the scatter's next position in each bucket
  std::vector<Entry> sorted_;                 // the small spheres, bucket by bucket (index order within)
  std::vector<std::uint32_t> keptI_, keptJ_;  // the walks' output, written ahead of the kept count
};

}  // namespace collide::world
