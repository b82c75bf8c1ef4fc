#include "cli/pairs_csv.hpp"

#include <cmath>
#include <stdexcept>

namespace collide::cli {

void readPairsCsv(std::istream& in, const std::string& name, LinkFormat format, SphereTable& spheres,
                  PairList& pairs, std::vector<std::uint8_t>& didNotFit) {
  readNumberCsv(
      in, name, format, {"x1", "y1", "z1", "r1", "x2", "y2", "z2", "r2"},
      [&](const double* v, const bool* unfit) {
        const auto a = static_cast<std::uint32_t>(spheres.size());
        spheres.push(v[0], v[1], v[2], v[3]);
        spheres.push(v[4], v[5], v[6], v[7]);
        pairs.push(a, a + 1);
        // A coordinate that became zero is still the nearest value; a radius is not (a
        // sphere of radius 0 is another body), nor is any value that became infinite.
        auto bad = [&](int c) { return unfit[c] && (c % 4 == 3 || std::isinf(v[c])); };
        didNotFit.push_back(bad(0) || bad(1) || bad(2) || bad(3));
        didNotFit.push_back(bad(4) || bad(5) || bad(6) || bad(7));
      },
      Overflow::Flag);
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
