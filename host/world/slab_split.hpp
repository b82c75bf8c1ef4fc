#pragma once
// A world with more spheres than one AFU run holds, cut into slabs along x (docs/host.md,
// "collide spheres"). Each slab owns a run of spheres in x order and also carries, as
// ghosts, every later sphere that could touch one of them; a run holds at most `cap` spheres.
// A pair is then found in exactly one run, the one of its first-owned sphere: keep a run's
// pair when at least one of its spheres is owned there (ghosts come only from later slabs, so
// a ghost-ghost pair belongs to a later run and a pair is never owned twice).
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace collide::world {

struct Slab {
  std::vector<std::uint32_t> spheres;  // positions into the input, ascending (so i < j stays i < j)
  std::vector<std::uint8_t> owned;     // beside them: 1 owned, 0 a ghost
  std::size_t ownedCount = 0;
};

// Two spheres touch only if |xi - xj| <= (ri + rj) * kSlabReach + kSlabSlack: the broad
// phase's own margin (9/8 of the sum of radii, far above any SCPU's rounding) and an absolute
// slack above every format's underflow allowance.
inline constexpr double kSlabReach = 1.125;
inline constexpr double kSlabSlack = 1e-15;

// `x`, `r`: the spheres' centres along x and radii as the AFU sees them (link format).
// Throws std::runtime_error when even one sphere and the spheres that may touch it exceed
// `cap` (too many within reach of one another along x).
std::vector<Slab> splitIntoSlabs(const std::vector<double>& x, const std::vector<double>& r, std::size_t cap);

}  // namespace collide::world
