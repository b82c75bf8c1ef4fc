#pragma once
// World mode's tuned CPU grid (`collide spheres --backend grid`): the contacts of
// `--backend simd` (grid + binary32 kernel, world/cpu_world.hpp) bit for bit and in the same
// order, found faster and on several threads (docs/host.md, "The tuned grid").
//  1. The members' binary32 values (one RNE rounding, as the kernel's gather).
//  2. Levels (world/cell_grid.hpp): level 0 holds every member, level k+1 the large spheres of
//     level k; each level sorts its small spheres by cell and tests each pair of neighbouring
//     cells once (the forward half shell), and each of its large spheres against the small
//     spheres in reach. Every pair of members is thus tested at most once, and every pair that
//     binary32 calls a hit exactly once. Threads take chunks of cells (then large spheres) from
//     a shared counter; each keeps its own hits.
//  3. The hits in (i, j) order: a counting sort by i over all threads' hits, then each i's few
//     j by insertion. The order is the pairs', so it does not depend on the threads.
//  4. Each contact's values by the simd kernel itself (gatherCollideF32) and its record flags
//     (hit, and coincident where d^2 = 0 in binary32), on slices of the contacts in parallel.
#include <atomic>
#include <memory>
#include <vector>

#include "world/cell_grid.hpp"
#include "world/thread_team.hpp"
#include "world/world_engine.hpp"

namespace collide::world {

struct TunedLevel {
  std::size_t spheres = 0, large = 0;
  double cellEdge = 0;
};

class TunedWorld final : public WorldEngine {
 public:
  // Sorted places a chunk of the walk holds: small enough to balance the threads on a
  // clustered world, large enough that its four binary searches are nothing.
  static constexpr std::size_t kChunk = 2048;

  explicit TunedWorld(unsigned threads = ThreadTeam::hardwareThreads());
  std::string name() const override;
  // broadNs: the binary32 copies, the levels and the walks (the binary32 decision included);
  // narrowNs: the contacts' values and flags; finishNs: ordering the hits.
  void collide(const SphereTable& s, WorldContacts& out, WorldTiming& time) override;
  unsigned threads() const { return team_.size(); }
  const std::vector<TunedLevel>& lastLevels() const { return levels_; }

 private:
  void walkLevel(const CellGrid& g, const SpheresF32& f);
  void orderHits(WorldContacts& out);
  void writeContacts(const SphereTable& s, WorldContacts& out);

  ThreadTeam team_;
  std::vector<std::uint32_t> members_, ids_;
  std::vector<float> x_, y_, z_, r_;
  std::vector<std::unique_ptr<CellGrid>> grids_;
  std::vector<TunedLevel> levels_;
  std::vector<HitList> hits_;  // one a thread
  std::vector<std::size_t> start_, cursor_;  // the hits by i: i's j at pj_[start_[i] .. start_[i+1])
  std::vector<std::uint32_t> pj_;            // member positions
  std::atomic<std::size_t> next_{0};
};

}  // namespace collide::world
