#include "cli/spheres_csv.hpp"

namespace collide::cli {

void readSpheresCsv(std::istream& in, const std::string& name, LinkFormat format, SphereTable& spheres) {
  readNumberCsv(in, name, format, {"x", "y", "z", "r"}, [&](const double* v, const bool*) { spheres.push(v[0], v[1], v[2], v[3]); });
}

void writeWorldContactsCsv(std::ostream& out, const world::WorldContacts& w) {
  const ContactSet& c = w.contacts;
  const std::string zeros = [&] {
    std::string z;
    for (int k = 0; k < 7; ++k) z += "," + hexFloat(0.0, c.format);
    return z;
  }();
  out << "i,j,px,py,pz,nx,ny,nz,depth,flags\n";
  std::size_t bad = 0;
  auto badRowsBefore = [&](std::uint64_t i) {  // bad spheres have no contacts: merge by i
    for (; bad < w.badSpheres.size() && w.badSpheres[bad] < i; ++bad)
      out << w.badSpheres[bad] << ',' << zeros << ',' << int{w.badFlags[bad]} << '\n';
  };
  for (std::size_t k = 0; k < w.pairs.size(); ++k) {
    badRowsBefore(w.pairs.i[k]);
    out << w.pairs.i[k] << ',' << w.pairs.j[k];
    for (const auto* col : {&c.px, &c.py, &c.pz, &c.nx, &c.ny, &c.nz, &c.depth})
      out << ',' << hexFloat((*col)[k], c.format);
    out << ',' << int{c.flags[k]} << '\n';
  }
  badRowsBefore(UINT64_MAX);
}

}  // namespace collide::cli
