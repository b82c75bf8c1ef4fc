#include "collide/model_backend.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "afu_contract.hpp"
#include "driver/afu_layout.hpp"

namespace collide {

ModelBackend::ModelBackend(const std::string& preset) : preset_(scpu::emulatedPreset(preset)) {}

void ModelBackend::collide(const SphereTable& s, const PairList& pairs, ContactSet& out) {
  // The table as the link carries it, and the spheres the driver would flag.
  linkTable_.resize(4 * s.size());
  outOfRange_.resize(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) outOfRange_[k] = driver::linkSphere(s, k, preset_.link, &linkTable_[4 * k]);
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
