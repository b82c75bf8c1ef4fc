#include "world/world_collider.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>

#include "afu_contract.hpp"
#include "collide/input_policy.hpp"

namespace collide::world {

namespace {
using Clock = std::chrono::steady_clock;
std::int64_t nsSince(Clock::time_point t0) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t0).count();
}
}  // namespace

void splitSpheres(const SphereTable& s, WorldContacts& out, std::vector<std::uint32_t>& members) {
  members.clear();
  for (std::uint32_t k = 0; k < s.size(); ++k) {
    const PairInput p = classifySphere(s, k);
    if (p == PairInput::Ok) {
      members.push_back(k);
      continue;
    }
    out.badSpheres.push_back(k);
    out.badFlags.push_back(p == PairInput::NonFinite ? contract::REC_NONFINITE : contract::REC_HOST_RANGE);
  }
}

void keepSortedHits(const PairList& pairs, const ContactSet& found, WorldContacts& out) {
  // A permutation, then a gather.
  std::vector<std::uint32_t> order(pairs.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return pairs.i[a] != pairs.i[b] ? pairs.i[a] < pairs.i[b] : pairs.j[a] < pairs.j[b];
  });
  for (auto k : order) {
    if (!found.hit[k]) continue;  // the policy rejected it
    out.pairs.push(pairs.i[k], pairs.j[k]);
    out.contacts.appendEntry(found, k);  // flags: the policy's
  }
}

void WorldCollider::collide(const SphereTable& s, WorldContacts& out, WorldTiming& time) {
  out = WorldContacts{};
  out.contacts.format = narrow_.format();
  time = WorldTiming{};
  splitSpheres(s, out, members_);
  broad_.prepare(s, members_);

  auto t0 = Clock::now();
  candidates_.clear();
  broad_.findPairs(s, members_, candidates_);
  time.broadNs = nsSince(t0);
  out.candidates = candidates_.size();

  // The narrow phase chunk by chunk, keeping the hits. Only hits are output, so the record
  // flags and the bad-pair policy (the `collide pairs` path) run on them alone; every member
  // is a good sphere, so the policy rejects none, but it is the one rule either way.
  ContactSet found;
  found.format = narrow_.format();
  PairList foundPairs;
  for (std::size_t a = 0; a < candidates_.size(); a += kChunkPairs) {
    const std::size_t b = std::min(candidates_.size(), a + kChunkPairs);
    t0 = Clock::now();
    chunk_.i.assign(candidates_.i.begin() + a, candidates_.i.begin() + b);
    chunk_.j.assign(candidates_.j.begin() + a, candidates_.j.begin() + b);
    time.finishNs += nsSince(t0);
    t0 = Clock::now();
    narrow_.collide(s, chunk_, chunkOut_);
    time.narrowNs += nsSince(t0);
    t0 = Clock::now();
    for (std::size_t k = 0; k < chunk_.size(); ++k) {
      if (!chunkOut_.hit[k]) continue;
      foundPairs.push(chunk_.i[k], chunk_.j[k]);
      found.appendEntry(chunkOut_, k);  // flags: a backend's own (rtl), else none yet
    }
    time.finishNs += nsSince(t0);
  }
  t0 = Clock::now();
  finishPairs(narrow_, s, foundPairs, found);
  time.finishNs += nsSince(t0);

  // Sorted by (i, j).
  t0 = Clock::now();
  keepSortedHits(foundPairs, found, out);
  time.finishNs += nsSince(t0);
}

}  // namespace collide::world
