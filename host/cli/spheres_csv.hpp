#pragma once
// World-mode CSV (`collide spheres`): input `x,y,z,r` (decimal or C99 hex floats, parsed
// into the backend's format with one rounding, as `collide pairs` reads), output
// `i,j,px,py,pz,nx,ny,nz,depth,flags`: one row per contact, i < j, sorted by (i, j), %a in
// the backend's format, the record flags byte in decimal; and one row per bad sphere with j
// empty and zero fields, its flags saying why it was never collided (8 non-finite, 32 out
// of ODE's range), in the same order by i.
#include <istream>
#include <ostream>
#include <string>

#include "batch/batch.hpp"
#include "cli/number_csv.hpp"
#include "world/world_collider.hpp"

namespace collide::cli {

// Sphere k is data row k. Throws CsvError "<name>:<line>: <what>".
void readSpheresCsv(std::istream& in, const std::string& name, LinkFormat format, SphereTable& spheres);

void writeWorldContactsCsv(std::ostream& out, const world::WorldContacts& w);

}  // namespace collide::cli
