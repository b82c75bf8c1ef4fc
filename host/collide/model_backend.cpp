#include "collide/model_backend.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "afu_contract.hpp"

namespace collide {

ModelBackend::ModelBackend(const std::string& preset) : preset_(scpu::emulatedPreset(preset)) {}

void ModelBackend::collide(const SphereTable& s, const PairList& pairs, ContactSet& out) {
  // The table as the link carries it, and the spheres the driver would flag (afu_layout's
  // writeSphereTable: a finite value that became infinite, a positive radius that became 0).
  const auto lf = numberFormat(preset_.link);
  linkTable_.resize(4 * s.size());
  outOfRange_.assign(s.size(), 0);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double v[4] = {s.x[k], s.y[k], s.z[k], s.r[k]};
    for (int c = 0; c < 4; ++c) {
      const double q = format::roundTo(v[c], lf);
      linkTable_[4 * k + c] = q;
      if (std::isfinite(v[c]) && !std::isfinite(q)) outOfRange_[k] = 1;
    }
    if (v[3] > 0 && linkTable_[4 * k + 3] == 0) outOfRange_[k] = 1;
  }
  for (std::size_t k = 0; k < pairs.size(); ++k)  // before anything is computed: no result half-written
    if (pairs.i[k] >= s.size() || pairs.j[k] >= s.size())
      throw std::out_of_range("backend " + name() + ": pair " + std::to_string(k) + " names sphere " +
                              std::to_string(std::max(pairs.i[k], pairs.j[k])) + " of a table of " +
                              std::to_string(s.size()));
  out.resize(pairs.size());
  out.format = preset_.link;
  out.flags.assign(pairs.size(), 0);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto i = pairs.i[k], j = pairs.j[k];
    const auto r = scpu::collidePair(preset_.arith, &linkTable_[4 * i], &linkTable_[4 * j]);
    out.hit[k] = r.hit;
    out.px[k] = r.v[0]; out.py[k] = r.v[1]; out.pz[k] = r.v[2];
    out.nx[k] = r.v[3]; out.ny[k] = r.v[4]; out.nz[k] = r.v[5];
    out.depth[k] = r.v[6];
    out.flags[k] = r.flags | ((outOfRange_[i] || outOfRange_[j]) ? contract::REC_HOST_RANGE : 0u);
  }
}

}  // namespace collide
