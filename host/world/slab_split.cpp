#include "world/slab_split.hpp"

#include <algorithm>
#include <exception>
#include <limits>
#include <numeric>
#include <string>

namespace collide::world {

namespace {

// The greedy cut along one axis; a refusal names the sphere as `names` (the caller's indices
// of the positions cut) and the axis.
std::vector<Slab> cut(const std::vector<double>& x, const std::vector<double>& r, std::size_t cap,
                      const std::vector<std::uint32_t>* names, const char* axis) {
  const std::size_t n = x.size();
  if (cap == 0) throw std::invalid_argument("splitIntoSlabs: a run must hold at least one sphere");
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return x[a] < x[b]; });
  double rMax = 0;
  for (double v : r) rMax = std::max(rMax, v);
  const double farReach = kSlabReach * rMax + kSlabSlack;  // the most a later sphere reaches back
  auto rightEdge = [&](std::uint32_t k) { return x[k] + kSlabReach * r[k] + kSlabSlack; };
  auto leftEdge = [&](std::uint32_t k) { return x[k] - kSlabReach * r[k]; };

  // Spheres of a run owning order[a, a + o): those, and every later one whose left edge
  // reaches the farthest right edge among them. The ghosts are listed into `ghosts`.
  std::vector<std::uint32_t> ghosts;
  auto runSize = [&](std::size_t a, std::size_t o, bool list) {
    double reach = -std::numeric_limits<double>::infinity();
    for (std::size_t p = a; p < a + o; ++p) reach = std::max(reach, rightEdge(order[p]));
    std::size_t g = 0;
    if (list) ghosts.clear();
    for (std::size_t p = a + o; p < n && x[order[p]] - farReach <= reach; ++p)
      if (leftEdge(order[p]) <= reach) {
        ++g;
        if (list) ghosts.push_back(order[p]);
      }
    return o + g;
  };

  std::vector<Slab> slabs;
  for (std::size_t a = 0; a < n;) {
    std::size_t o = std::min(cap, n - a);
    if (runSize(a, o, false) > cap) {
      if (runSize(a, 1, false) > cap)
        throw std::runtime_error("world mode: sphere " + std::to_string(names ? (*names)[order[a]] : order[a]) +
                                 " and the " + std::to_string(runSize(a, 1, false) - 1) + " spheres that may touch it along " +
                                 axis + " exceed the " + std::to_string(cap) +
                                 " spheres an AFU run holds; this world cannot be cut into runs");
      std::size_t lo = 1, hi = o;  // runSize(lo) fits, runSize(hi) does not; it grows with o
      while (hi - lo > 1) {
        const std::size_t mid = lo + (hi - lo) / 2;
        (runSize(a, mid, false) <= cap ? lo : hi) = mid;
      }
      o = lo;
    }
    runSize(a, o, true);
    Slab s;
    std::vector<std::pair<std::uint32_t, std::uint8_t>> all;
    for (std::size_t p = a; p < a + o; ++p) all.emplace_back(order[p], 1);
    for (auto g : ghosts) all.emplace_back(g, 0);
    std::sort(all.begin(), all.end());
    for (const auto& [k, own] : all) { s.spheres.push_back(k); s.owned.push_back(own ? kOwnedBoth : 0); }
    s.ownedCount = o;
    slabs.push_back(std::move(s));
    a += o;
  }
  return slabs;
}

// Each slab cut along y into strips of at most `cap`: the boxes.
std::vector<Slab> boxesOf(const std::vector<Slab>& slabs, const std::vector<double>& y, const std::vector<double>& r,
                          std::size_t cap) {
  std::vector<Slab> boxes;
  for (const Slab& slab : slabs) {
    std::vector<double> sy, sr;
    for (auto p : slab.spheres) { sy.push_back(y[p]); sr.push_back(r[p]); }
    std::vector<Slab> strips;
    try {
      strips = cut(sy, sr, cap, &slab.spheres, "y");
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(std::string(e.what()) + " along x, nor into boxes along x and y (a slab of " +
                               std::to_string(slab.spheres.size()) + " spheres along x, cut along y)");
    }
    for (const Slab& strip : strips) {
      Slab b;
      for (std::size_t k = 0; k < strip.spheres.size(); ++k) {
        const auto q = strip.spheres[k];  // a position in the slab, so ascending stays ascending
        b.spheres.push_back(slab.spheres[q]);
        const std::uint8_t own = static_cast<std::uint8_t>((slab.owned[q] ? kOwnedX : 0) | (strip.owned[k] ? kOwnedY : 0));
        b.owned.push_back(own);
        b.ownedCount += own == kOwnedBoth;
      }
      boxes.push_back(std::move(b));
    }
  }
  return boxes;
}

// Slab widths past `cap` by doubling, 2 cap, 4 cap, ..., and last the whole world (`n`), where
// one slab always fits: the widths tried where slabs of one run do not.
std::vector<std::size_t> doublings(std::size_t cap, std::size_t n) {
  std::vector<std::size_t> widths;
  for (std::size_t w = 2 * cap; w < n; w *= 2) widths.push_back(w);
  widths.push_back(n);
  return widths;
}

}  // namespace

std::vector<Slab> splitIntoSlabs(const std::vector<double>& x, const std::vector<double>& r, std::size_t cap) {
  return cut(x, r, cap, nullptr, "x");
}

std::vector<Slab> splitIntoBoxes(const std::vector<double>& x, const std::vector<double>& y,
                                 const std::vector<double>& r, std::size_t cap) {
  try {
    return splitIntoSlabs(x, r, cap);
  } catch (const std::runtime_error&) {  // some sphere's x slice is too full: boxes
  }
  // The narrowest slabs along x that fit: a run of all spheres always does.
  const std::vector<std::size_t> widths = doublings(cap, x.size());
  for (std::size_t i = 0;; ++i) {
    std::vector<Slab> slabs;
    try {
      slabs = splitIntoSlabs(x, r, widths[i]);
    } catch (const std::runtime_error&) {  // too narrow for some sphere's neighbours
      if (i + 1 == widths.size()) throw;
      continue;
    }
    return boxesOf(slabs, y, r, cap);
  }
}

std::size_t sphereCount(const std::vector<Slab>& runs) {
  std::size_t n = 0;
  for (const Slab& s : runs) n += s.spheres.size();
  return n;
}

std::size_t cutCost(const std::vector<Slab>& runs, std::size_t cap) {
  // A run also costs work that does not grow with its spheres (the broad phase's fixed passes,
  // up to about cap / 16 cycles in the AFU, against about a cycle a sphere): a run more is
  // worth it only for that many spheres fewer.
  return sphereCount(runs) + runs.size() * (cap / 16);
}

std::vector<Slab> splitIntoRuns(const std::vector<double>& x, const std::vector<double>& y,
                                const std::vector<double>& r, std::size_t cap) {
  auto cost = [&](const std::vector<Slab>& c) { return cutCost(c, cap); };
  std::vector<Slab> best;
  bool any = false;
  auto consider = [&](std::vector<Slab>&& c) {
    if (!any || cost(c) < cost(best) || (cost(c) == cost(best) && c.size() < best.size())) best = std::move(c);
    any = true;
  };
  try {
    consider(splitIntoSlabs(x, r, cap));
  } catch (const std::runtime_error&) {  // some sphere's x slice is too full: boxes only
  }
  // Boxes: slabs k runs wide, each cut along y, each width tried once: k = 2, 3, 4, 6, 9, ...
  // (growing by half); where slabs of one run do not fit, also the doublings splitIntoBoxes
  // tries and the whole world (one slab always fits), so that boxes are found where it finds them.
  const std::size_t n = x.size();
  std::vector<std::size_t> widths;
  for (std::size_t k = 2; k * cap < n; k += std::max<std::size_t>(1, k / 2)) widths.push_back(k * cap);
  if (!any) {
    const std::vector<std::size_t> d = doublings(cap, n);
    widths.insert(widths.end(), d.begin(), d.end());
  }
  std::sort(widths.begin(), widths.end());
  widths.erase(std::unique(widths.begin(), widths.end()), widths.end());
  std::exception_ptr narrowest;  // why the narrowest slabs that fit gave no boxes
  for (std::size_t w : widths) {
    std::vector<Slab> slabs;
    try {
      slabs = splitIntoSlabs(x, r, w);
    } catch (const std::runtime_error&) {  // too narrow for some sphere's neighbours
      continue;
    }
    try {
      consider(boxesOf(slabs, y, r, cap));
    } catch (const std::runtime_error&) {
      if (!any && !narrowest) narrowest = std::current_exception();
    }
  }
  if (!any) std::rethrow_exception(narrowest);
  // The smallest run first: through the AFU's run queue, only the first run's table is read
  // while nothing else happens (each later table loads during the run before it), and which
  // run owns a pair does not depend on the order they run in.
  const auto smallest = std::min_element(best.begin(), best.end(), [](const Slab& a, const Slab& b) {
    return a.spheres.size() < b.spheres.size();
  });
  std::rotate(best.begin(), smallest, smallest + 1);
  return best;
}

}  // namespace collide::world
