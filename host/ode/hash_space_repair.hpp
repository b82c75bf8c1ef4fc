#pragma once
// dSpaceCollide, made whole for ODE's hash space.
//
// ODE 0.16's hash space (dxHashSpace::collide in collision_space.cpp, unchanged up to 0.16.6)
// finds a cell's slot as (level*1000 + x*100 + y*10 + z) % size in unsigned long arithmetic,
// starting each z-run at the run's first z. When a box's run starts at a z so negative that
// the sum wraps below zero (level >= 0, x >= 0, y >= 0, z < -(level*1000 + x*100 + y*10)),
// its cells land in other slots than the same cells reached by an unwrapped run, because 2^64
// is no multiple of the (prime) table size: a pair whose boxes share only such a cell is never
// reported. Near the origin this is common: at level 0, cell (0, 0, 0) of a box reaching below
// z = 0 is one of them.
//
// collideSpace runs dSpaceCollide, then gives the callback each pair ODE skipped for that
// reason: every enabled geom whose run wraps is tested against every other geom of the space
// with ODE's own filters (bodies, category and collide bits, overlapping AABBs), and pairs ODE
// already reported are not repeated. Other space kinds, and hash spaces where no run wraps
// (one O(n) pass finds out), cost nothing more than that pass.
#include <vector>

#include <ode/ode.h>

namespace collide::ode {

void collideSpace(dSpaceID space, void* data, dNearCallback* callback);

// The geoms of a hash space whose cell runs wrap (their pairs may be dropped by ODE); empty for
// other kinds of space. Exposed for tests.
std::vector<dGeomID> wrappingGeoms(dSpaceID space);

}  // namespace collide::ode
