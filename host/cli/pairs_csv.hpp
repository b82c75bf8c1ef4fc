#pragma once
// Vector-mode CSV: input `x1,y1,z1,r1,x2,y2,z2,r2` (decimal or C99 hex floats),
// output `pair,hit,px,py,pz,nx,ny,nz,depth,flags` with %a hex floats in the link format and
// the record flags byte (docs/afu-interface.md) in decimal.
#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "batch/contact_set.hpp"
#include "cli/number_csv.hpp"

namespace collide::cli {

// Pair k becomes spheres 2k (sphere 1) and 2k+1 (sphere 2). Values are parsed straight
// into the link format with one correct rounding (format::parseInto). A value that does not
// fit it (a finite value that becomes infinite, a non-zero radius that becomes zero) is
// kept as rounded and its sphere marked in didNotFit (one entry per sphere), for
// collidePairs to flag the pair (REC_HOST_RANGE): never a whole-file error.
// Throws CsvError "<name>:<line>: <what>" on a malformed file.
void readPairsCsv(std::istream& in, const std::string& name, LinkFormat format,
                  SphereTable& spheres, PairList& pairs, std::vector<std::uint8_t>& didNotFit);

void writeContactsCsv(std::ostream& out, const ContactSet& contacts);

}  // namespace collide::cli
