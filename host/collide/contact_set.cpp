#include "collide/contact_set.hpp"

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

}  // namespace collide
