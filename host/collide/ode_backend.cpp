#include "collide/ode_backend.hpp"

#include <stdexcept>

#include "collide/input_policy.hpp"

namespace collide {

OdeBackend::OdeBackend() : scratch1_(dCreateSphere(nullptr, 1)), scratch2_(dCreateSphere(nullptr, 1)) {}

OdeBackend::~OdeBackend() {
  dGeomDestroy(scratch1_);
  dGeomDestroy(scratch2_);
}

void OdeBackend::collide(const SphereTable& s, const PairList& pairs, ContactSet& out) {
  const std::size_t n = pairs.size();
  const bool world = geoms_ && !geoms_->empty();
  if (world && geoms_->size() != s.size()) throw std::logic_error("OdeBackend: bound geoms do not match the sphere table");
  out.resize(n);
  out.format = LinkFormat::Binary64;
  for (std::size_t k = 0; k < n; ++k) {
    const auto a = pairs.i[k], b = pairs.j[k];
    // A pair ODE cannot take (a non-finite value or a negative radius, input_policy.hpp)
    // never reaches it: no contact here, flagged by the policy. Vector mode computes every
    // other pair (no hash space here). A world's spheres were checked by the scene and at
    // every step.
    if (!world && !vectorComputes(classifyVectorPair(s, a, b))) continue;
    dGeomID g1 = scratch1_, g2 = scratch2_;
    if (world) {
      g1 = (*geoms_)[a];
      g2 = (*geoms_)[b];
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
