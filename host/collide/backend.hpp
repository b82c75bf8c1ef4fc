#pragma once
// A collision backend computes dCollideSpheres for every pair of a batch.
#include <memory>
#include <string>

#include "batch/batch.hpp"
#include "batch/contact_set.hpp"

namespace collide {

class CollisionBackend {
 public:
  virtual ~CollisionBackend() = default;
  virtual std::string name() const = 0;
  // The number format the results are exact in (what `collide pairs` prints).
  virtual LinkFormat format() const = 0;
  // out.size() == pairs.size() afterwards; entry k is pair k (dense, in pair order).
  virtual void collide(const SphereTable& spheres, const PairList& pairs, ContactSet& out) = 0;
  // Whether collide() fills out.flags itself (the AFU's record flags); else
  // setCpuRecordFlags computes them where they are wanted (contact_flags.hpp).
  virtual bool setsRecordFlags() const { return false; }
};

}  // namespace collide
