#pragma once
// Vector-mode CSV: input `x1,y1,z1,r1,x2,y2,z2,r2` (decimal or C99 hex floats),
// output `pair,hit,px,py,pz,nx,ny,nz,depth,flags` with %a hex floats in the link format and
// the record flags byte (docs/afu-interface.md) in decimal.
#include <istream>
#include <ostream>
#include <string>

#include "batch/batch.hpp"
#include "batch/contact_set.hpp"
#include "cli/number_csv.hpp"

namespace collide::cli {

// Pair k becomes spheres 2k (sphere 1) and 2k+1 (sphere 2). Values are parsed straight
// into the link format with one correct rounding (format::parseInto), and a value that
// overflows it is an error.
// Throws CsvError "<name>:<line>: <what>".
void readPairsCsv(std::istream& in, const std::string& name, LinkFormat format,
                  SphereTable& spheres, PairList& pairs);

void writeContactsCsv(std::ostream& out, const ContactSet& contacts);

}  // namespace collide::cli
