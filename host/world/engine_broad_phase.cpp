#include "world/engine_broad_phase.hpp"

#include <algorithm>
#include <iterator>

namespace collide::world {

namespace {
std::vector<std::uint64_t> sortedKeys(const PairList& p) {
  std::vector<std::uint64_t> k(p.size());
  for (std::size_t n = 0; n < p.size(); ++n) k[n] = (std::uint64_t{p.i[n]} << 32) | p.j[n];
  std::sort(k.begin(), k.end());
  return k;
}
}  // namespace

EngineDiff compareContacts(const PairList& engine, const PairList& exact) {
  const auto a = sortedKeys(engine), b = sortedKeys(exact);
  std::vector<std::uint64_t> d;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(d));
  EngineDiff out;
  out.onlyEngine = d.size();
  d.clear();
  std::set_difference(b.begin(), b.end(), a.begin(), a.end(), std::back_inserter(d));
  out.onlyExact = d.size();
  return out;
}

}  // namespace collide::world
