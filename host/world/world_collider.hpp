#pragma once
// World mode on the CPU: every contact of a sphere table, found by a broad phase and
// computed by a backend's narrow phase (CollisionBackend::collide, then its record flags and
// the bad-pair policy: the `collide pairs` path, collide/input_policy.hpp).
// A sphere the policy rejects (non-finite, or outside ODE's range) never enters the broad
// phase: it is listed once in badSpheres with its flag, so nothing is dropped silently.
#include <cstdint>
#include <vector>

#include "batch/batch.hpp"
#include "batch/contact_set.hpp"
#include "collide/backend.hpp"
#include "world/broad_phase.hpp"

namespace collide::world {

struct WorldContacts {
  PairList pairs;        // the contacts' spheres, i < j, sorted by (i, j)
  ContactSet contacts;   // entry k belongs to pairs k (all hits), with its record flags
  std::vector<std::uint32_t> badSpheres;  // ascending
  std::vector<std::uint8_t> badFlags;     // REC_NONFINITE or REC_HOST_RANGE, beside them
  std::size_t candidates = 0;             // pairs the broad phase found
  // AFU world mode only: candidates the arithmetic flagged (overflow, invalid) that are no
  // contact. The AFU writes contacts only in world mode, so they are counted, not listed
  // (summed over runs: a pair two runs both hold counts twice).
  std::size_t flaggedMisses = 0;
};

struct WorldTiming {
  std::int64_t broadNs = 0;   // BroadPhase::findPairs
  std::int64_t narrowNs = 0;  // CollisionBackend::collide on the candidates
  std::int64_t finishNs = 0;  // flags, bad-pair policy, keeping the hits, sorting by (i, j)
};

// The spheres the input policy takes (`members`, ascending) and the rest, listed with their
// flag in out.badSpheres/badFlags. Every world-mode path starts here.
void splitSpheres(const SphereTable& s, WorldContacts& out, std::vector<std::uint32_t>& members);
// The hits of `found` (entry k belongs to pairs k) into out.pairs/out.contacts, sorted by (i, j).
void keepSortedHits(const PairList& pairs, const ContactSet& found, WorldContacts& out);

class WorldCollider {
 public:
  // Candidates go to the narrow phase this many at a time (the scratch stays in L2).
  static constexpr std::size_t kChunkPairs = 16384;

  WorldCollider(BroadPhase& broad, CollisionBackend& narrow) : broad_(broad), narrow_(narrow) {}
  void collide(const SphereTable& s, WorldContacts& out, WorldTiming& time);

 private:
  BroadPhase& broad_;
  CollisionBackend& narrow_;
  std::vector<std::uint32_t> members_;
  PairList candidates_, chunk_;
  ContactSet chunkOut_;
};

}  // namespace collide::world
