#include "batch/contact_set.hpp"

#include <algorithm>
#include <numeric>

namespace collide {

std::size_t ContactSet::hits() const {
  return static_cast<std::size_t>(std::count(hit.begin(), hit.end(), std::uint8_t{1}));
}

void ContactSet::resize(std::size_t n) {
  hit.assign(n, 0);
  flags.assign(n, 0);
  for (auto* v : {&px, &py, &pz, &nx, &ny, &nz, &depth}) v->assign(n, 0.0);
}

void ContactSet::resizeForOverwrite(std::size_t n) {
  hit.resize(n);
  flags.resize(n);
  for (auto* v : {&px, &py, &pz, &nx, &ny, &nz, &depth}) v->resize(n);
}

void ContactSet::setEntry(std::size_t to, const ContactSet& src, std::size_t k) {
  hit[to] = src.hit[k];
  if (src.flags.size() == src.size()) flags[to] = src.flags[k];
  px[to] = src.px[k]; py[to] = src.py[k]; pz[to] = src.pz[k];
  nx[to] = src.nx[k]; ny[to] = src.ny[k]; nz[to] = src.nz[k];
  depth[to] = src.depth[k];
}

void ContactSet::appendEntry(const ContactSet& src, std::size_t k) {
  const std::size_t to = size();
  hit.push_back(0);
  if (src.flags.size() == src.size()) flags.push_back(0);
  for (auto* v : {&px, &py, &pz, &nx, &ny, &nz, &depth}) v->push_back(0.0);
  setEntry(to, src, k);
}

}  // namespace collide
