#include "ode/hash_space_repair.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <set>
#include <utility>

namespace collide::ode {

namespace {

// ODE's findLevel: the level whose cell size 2^level is the box's largest side rounded up.
int findLevel(const dReal aabb[6]) {
  for (int i = 0; i < 6; ++i)
    if (std::isinf(aabb[i])) return INT_MAX;
  dReal q = std::max({aabb[1] - aabb[0], aabb[3] - aabb[2], aabb[5] - aabb[4]});
  int level;
  std::frexp(q, &level);
  return level;
}

struct Box {
  dGeomID geom;
  int level;
  int cells[6];  // the box's cells at its own level: x0, x1, y0, y1, z0, z1
};

// Whether any z-run of the box's walk, at its level or a coarser one up to maxLevel, starts
// below zero once the level and the row's x and y are added (ODE's getVirtualAddressBase).
bool wraps(const Box& b, int maxLevel) {
  int c[6];
  std::copy(b.cells, b.cells + 6, c);
  for (int level = b.level; level <= maxLevel; ++level) {
    // A negative level, x or y is a huge unsigned number there: no wrap.
    if (level >= 0 && c[1] >= 0 && c[3] >= 0 && c[4] < 0) {
      const long long base = 1000LL * level + 100LL * std::max(c[0], 0) + 10LL * std::max(c[2], 0);
      if (base + c[4] < 0) return true;
    }
    for (int& v : c) v >>= 1;  // floor division, as ODE's db[i] >>= 1
  }
  return false;
}

bool overlap(dGeomID a, dGeomID b) {
  dReal p[6], q[6];
  dGeomGetAABB(a, p);
  dGeomGetAABB(b, q);
  return !(p[0] > q[1] || p[1] < q[0] || p[2] > q[3] || p[3] < q[2] || p[4] > q[5] || p[5] < q[4]);
}

// ODE's collideAABBs filters (its AABBTest hook is internal; for spheres it passes everything).
bool mayCollide(dGeomID a, dGeomID b) {
  const dBodyID ba = dGeomGetBody(a), bb = dGeomGetBody(b);
  if (ba && ba == bb) return false;
  if (!((dGeomGetCategoryBits(a) & dGeomGetCollideBits(b)) || (dGeomGetCategoryBits(b) & dGeomGetCollideBits(a))))
    return false;
  return overlap(a, b);
}

using GeomPair = std::pair<dGeomID, dGeomID>;
GeomPair ordered(dGeomID a, dGeomID b) { return a < b ? GeomPair{a, b} : GeomPair{b, a}; }

// Records the pairs ODE reports that touch a wrapping geom, passing every pair on.
struct Recorder {
  void* data;
  dNearCallback* callback;
  const std::set<dGeomID>* wrapping;
  std::set<GeomPair> seen;
  static void near(void* self, dGeomID a, dGeomID b) {
    auto* r = static_cast<Recorder*>(self);
    if (r->wrapping->count(a) || r->wrapping->count(b)) r->seen.insert(ordered(a, b));
    r->callback(r->data, a, b);
  }
};

}  // namespace

std::vector<dGeomID> wrappingGeoms(dSpaceID space) {
  std::vector<dGeomID> out;
  if (dSpaceGetClass(space) != dHashSpaceClass) return out;
  dSpaceClean(space);  // up-to-date AABBs, as dSpaceCollide computes them
  int minLevel = 0, maxLevel = 0;
  dHashSpaceGetLevels(space, &minLevel, &maxLevel);
  std::vector<Box> boxes;
  int used = minLevel - 1;  // the coarsest level in use: ODE walks every box up to it
  const int n = dSpaceGetNumGeoms(space);
  for (int i = 0; i < n; ++i) {
    dGeomID g = dSpaceGetGeom(space, i);
    if (!dGeomIsEnabled(g)) continue;
    dReal aabb[6];
    dGeomGetAABB(g, aabb);
    int level = std::max(findLevel(aabb), minLevel);
    if (level > maxLevel) continue;  // ODE tests these against every box directly
    used = std::max(used, level);
    Box b{g, level, {}};
    const dReal recip = 1 / std::ldexp(dReal(1), level);  // exact, as ODE's
    for (int k = 0; k < 6; ++k) b.cells[k] = static_cast<int>(std::floor(aabb[k] * recip));
    boxes.push_back(b);
  }
  for (const auto& b : boxes)
    if (wraps(b, used)) out.push_back(b.geom);
  return out;
}

void collideSpace(dSpaceID space, void* data, dNearCallback* callback) {
  const auto wrapList = wrappingGeoms(space);
  if (wrapList.empty()) {
    dSpaceCollide(space, data, callback);
    return;
  }
  const std::set<dGeomID> wrapping(wrapList.begin(), wrapList.end());
  Recorder rec{data, callback, &wrapping, {}};
  dSpaceCollide(space, &rec, &Recorder::near);
  const int n = dSpaceGetNumGeoms(space);
  for (dGeomID a : wrapList) {
    for (int i = 0; i < n; ++i) {
      dGeomID b = dSpaceGetGeom(space, i);
      if (b == a || !dGeomIsEnabled(b) || !mayCollide(a, b)) continue;
      if (rec.seen.insert(ordered(a, b)).second) callback(data, a, b);
    }
  }
}

}  // namespace collide::ode
