#include "cli/pairs_csv.hpp"

#include <stdexcept>

namespace collide::cli {

void readPairsCsv(std::istream& in, const std::string& name, LinkFormat format, SphereTable& spheres,
                  PairList& pairs) {
  readNumberCsv(in, name, format, {"x1", "y1", "z1", "r1", "x2", "y2", "z2", "r2"}, [&](const double* v) {
    const auto a = static_cast<std::uint32_t>(spheres.size());
    spheres.push(v[0], v[1], v[2], v[3]);
    spheres.push(v[4], v[5], v[6], v[7]);
    pairs.push(a, a + 1);
  });
}

void writeContactsCsv(std::ostream& out, const ContactSet& c) {
  if (c.flags.size() != c.size()) throw std::logic_error("writeContactsCsv: the contact set has no flags");
  out << "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n";
  for (std::size_t k = 0; k < c.size(); ++k) {
    out << k << ',' << int{c.hit[k]};
    for (const auto* col : {&c.px, &c.py, &c.pz, &c.nx, &c.ny, &c.nz, &c.depth})
      out << ',' << hexFloat((*col)[k], c.format);
    out << ',' << int{c.flags[k]} << '\n';
  }
}

}  // namespace collide::cli
