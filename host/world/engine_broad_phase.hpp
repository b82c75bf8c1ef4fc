#pragma once
// Another engine's broad phase for world mode (Bullet, FCL: bullet_broad_phase.hpp,
// fcl_broad_phase.hpp). Its candidates go to the simd kernel like our grid's, so the contacts
// are simd's byte for byte; the engine's own narrow phase can still be run on the same
// candidates (engineContacts), to time it and to count where its contact decision differs
// from binary32's.
//
// Every sphere's box for the engine is grown to its binary32 reach (candidateReach below),
// so that the engine's box test keeps every pair binary32 calls a hit: on an axis, binary32
// calls no pair a hit whose centres are more than (r1 + r2)(1 + 2^-21) apart (its errors are
// a few units in 2^-24, docs/host.md "The tuned grid"), or less than 2^-59 apart where the
// squares underflow.
#include <cstdint>
#include <string>

#include "batch/batch.hpp"
#include "world/broad_phase.hpp"

namespace collide::world {

// Half the edge of the box an engine gets for a sphere of radius r (r a binary32 value):
// r (1 + 2^-20) + 2^-60, at least r (1 + 2^-21) + 2^-60 after a binary32 rounding.
inline double candidateReach(double r) { return r * (1 + 0x1p-20) + 0x1p-60; }

// An engine's contacts against ours (both as (min, max) pairs, any order): how many pairs only
// the engine calls a contact, and how many only binary32 does.
struct EngineDiff {
  std::size_t onlyEngine = 0, onlyExact = 0;
};
EngineDiff compareContacts(const PairList& engine, const PairList& exact);

class EngineBroadPhase : public BroadPhase {
 public:
  // The engine's own narrow phase on the pairs of the last findPairs: the pairs it calls a
  // contact, each as (min, max), in its order.
  virtual void engineContacts(const SphereTable& s, PairList& out) = 0;
  // What that narrow phase is, for the stderr line and the summary.
  virtual std::string engineNarrowName() const = 0;
};

}  // namespace collide::world
