#pragma once
// A world with more spheres than one AFU run holds, cut into slabs along x, or into boxes
// along x and y where slabs cannot hold it (docs/host.md, "collide spheres"). Each slab owns a
// run of spheres in x order and also carries, as ghosts, every later sphere that could touch
// one of them; a run holds at most `cap` spheres.
// A pair is then found in exactly one run, the one of its first-owned sphere: keep a run's
// pair when at least one of its spheres is owned there (ghosts come only from later slabs, so
// a ghost-ghost pair belongs to a later run and a pair is never owned twice).
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace collide::world {

struct Slab {
  std::vector<std::uint32_t> spheres;  // positions into the input, ascending (so i < j stays i < j)
  // Beside them, ownership bits: kOwnedX (owned by its slab along x), kOwnedY (owned by its
  // strip along y). A run keeps a pair when the two spheres' bits together are kOwnedBoth; a
  // slab cut along x alone marks its owned spheres kOwnedBoth and its ghosts 0.
  std::vector<std::uint8_t> owned;
  std::size_t ownedCount = 0;  // spheres marked kOwnedBoth
};
inline constexpr std::uint8_t kOwnedX = 1, kOwnedY = 2, kOwnedBoth = kOwnedX | kOwnedY;

// Whether a run keeps the pair of its spheres at positions a and b.
inline bool keepsPair(const Slab& s, std::size_t a, std::size_t b) { return (s.owned[a] | s.owned[b]) == kOwnedBoth; }

// Two spheres touch only if |xi - xj| <= (ri + rj) * kSlabReach + kSlabSlack: the broad
// phase's own margin (9/8 of the sum of radii, far above any SCPU's rounding) and an absolute
// slack above every format's underflow allowance.
inline constexpr double kSlabReach = 1.125;
inline constexpr double kSlabSlack = 1e-15;

// `x`, `r`: the spheres' centres along x and radii as the AFU sees them (link format).
// Throws std::runtime_error when even one sphere and the spheres that may touch it exceed
// `cap` (too many within reach of one another along x).
std::vector<Slab> splitIntoSlabs(const std::vector<double>& x, const std::vector<double>& r, std::size_t cap);

// Slabs along x when they fit; otherwise boxes: slabs along x of more than `cap` spheres (the
// fewest that fit, doubling), each cut along y into strips of at most `cap` with the same rule
// (a strip's ghosts come from its slab's later strips). A pair is then kept in exactly one
// box: the slab that owns one of its spheres along x, and in it the strip that owns one along
// y. Throws std::runtime_error, naming the sphere, when even that does not fit.
std::vector<Slab> splitIntoBoxes(const std::vector<double>& x, const std::vector<double>& y,
                                 const std::vector<double>& r, std::size_t cap);

// Spheres in all runs of a cut, ghosts included: what the link carries and the broad phase
// works through.
std::size_t sphereCount(const std::vector<Slab>& runs);

// What splitIntoRuns minimizes: the spheres in all runs plus cap / 16 for each run (a run's
// fixed passes in the broad phase, at about a cycle a sphere).
std::size_t cutCost(const std::vector<Slab>& runs, std::size_t cap);

// The cut of least cutCost (the fewest spheres in all, a run counted as cap / 16 spheres more)
// among slabs along x (where they fit) and boxes whose slabs along x hold 2, 3, 4, 6, 9, ...
// runs' worth before their cut along y (where slabs do not fit, also the widths splitIntoBoxes
// tries, so boxes are found wherever it finds them). Thin slabs carry a ghost layer on one side of every run; near-square columns carry two
// thinner ones, about 2 / sqrt(runs) of a slab's share (a uniform cloud of 65,536 spheres in
// runs of 4,096: 0.5 more spheres in slabs, about 0.2 in columns). The smallest run comes
// first (its table is the one read with nothing to overlap). Throws as splitIntoBoxes.
std::vector<Slab> splitIntoRuns(const std::vector<double>& x, const std::vector<double>& y,
                                const std::vector<double>& r, std::size_t cap);

}  // namespace collide::world
