#include "collide/ode_backend.hpp"

#include <sstream>
#include <stdexcept>
#include <string>

#include "ode/ode_limits.hpp"

namespace collide {

OdeBackend::OdeBackend() : scratch1_(dCreateSphere(nullptr, 1)), scratch2_(dCreateSphere(nullptr, 1)) {}

OdeBackend::~OdeBackend() {
  dGeomDestroy(scratch1_);
  dGeomDestroy(scratch2_);
}

namespace {
std::string num(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}
// Vector mode hands the table's values to ODE, which aborts on a bad radius and whose
// results beyond the sane range mean nothing: refused first, naming the pair and the
// column (x1..r2, as in `collide pairs` input).
void requireSane(const SphereTable& s, const PairList& pairs) {
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    for (int side = 0; side < 2; ++side) {
      const std::uint32_t a = side == 0 ? pairs.i[k] : pairs.j[k];
      const std::string n = std::to_string(side + 1);
      auto bad = [&](const std::string& col, double v, const std::string& range) {
        throw std::invalid_argument("ode: pair " + std::to_string(k) + ": " + col + n + " = " + num(v) +
                                    " is outside the sane range " + range + " (docs/host.md, \"What reaches ODE\")");
      };
      if (!ode::saneRadius(s.r[a])) bad("r", s.r[a], "(0, " + num(ode::kMaxRadiusM) + "] m");
      const double c[3] = {s.x[a], s.y[a], s.z[a]};
      for (int d = 0; d < 3; ++d)
        if (!ode::saneCoordinate(c[d]))
          bad(std::string(1, "xyz"[d]), c[d], "[-" + num(ode::kMaxCoordinateM) + ", " + num(ode::kMaxCoordinateM) + "] m");
    }
  }
}
}  // namespace

void OdeBackend::collide(const SphereTable& s, const PairList& pairs, ContactSet& out) {
  const std::size_t n = pairs.size();
  const bool world = !s.geom.empty();
  if (!world) requireSane(s, pairs);  // a world's spheres were checked by the scene and each step
  out.resize(n);
  out.format = LinkFormat::Binary64;
  for (std::size_t k = 0; k < n; ++k) {
    const auto a = pairs.i[k], b = pairs.j[k];
    dGeomID g1 = scratch1_, g2 = scratch2_;
    if (world) {
      g1 = s.geom[a];
      g2 = s.geom[b];
    } else {
      dGeomSphereSetRadius(g1, s.r[a]);
      dGeomSetPosition(g1, s.x[a], s.y[a], s.z[a]);
      dGeomSphereSetRadius(g2, s.r[b]);
      dGeomSetPosition(g2, s.x[b], s.y[b], s.z[b]);
    }
    // dCollide(o1, o2) on two spheres runs dCollideSpheres(o1, o2) unreversed: the
    // normal points from o2 to o1, i.e. from sphere j to sphere i.
    dContactGeom c;
    if (dCollide(g1, g2, 1, &c, sizeof(dContactGeom)) == 0) continue;
    out.hit[k] = 1;
    out.px[k] = c.pos[0]; out.py[k] = c.pos[1]; out.pz[k] = c.pos[2];
    out.nx[k] = c.normal[0]; out.ny[k] = c.normal[1]; out.nz[k] = c.normal[2];
    out.depth[k] = c.depth;
  }
}

}  // namespace collide
