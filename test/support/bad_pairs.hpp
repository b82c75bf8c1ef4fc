#pragma once
// Pairs of every kind the input policy rejects or flags, with a good contact first (test only).
#include <limits>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "collide/input_policy.hpp"

namespace collide::test {

struct BadPairs {
  SphereTable spheres;
  PairList pairs;
  std::vector<PairInput> want;         // a scene's rule (classifyPair)
  std::vector<VectorInput> wantVector;  // vector mode's (classifyVectorPair)
  std::vector<std::string> what;
};

inline BadPairs badPairs() {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  BadPairs b;
  auto add = [&](double x1, double r1, double x2, double r2, PairInput w, VectorInput v, const std::string& what) {
    const auto i = static_cast<std::uint32_t>(b.spheres.size());
    b.spheres.push(x1, 0.5, 0, r1);
    b.spheres.push(x2, 0.5, 0, r2);
    b.pairs.push(i, i + 1);
    b.want.push_back(w);
    b.wantVector.push_back(v);
    b.what.push_back(what);
  };
  using P = PairInput;
  using V = VectorInput;
  add(0, 1, 1.5, 1, P::Ok, V::Ok, "an ordinary contact");
  add(nan, 1, 1.5, 1, P::NonFinite, V::NonFinite, "a NaN coordinate");
  add(0, 1, inf, 1, P::NonFinite, V::NonFinite, "an infinite coordinate");
  add(0, inf, 1.5, 1, P::NonFinite, V::NonFinite, "an infinite radius (the SCPU calls it a contact with NaN fields)");
  add(0, nan, 1.5, 1, P::NonFinite, V::NonFinite, "a NaN radius");
  add(0, -1, 1.5, 2, P::OutOfRange, V::NegativeRadius, "a negative radius (r1 + r2 still covers the distance)");
  add(0, -0.0, 0, 1, P::OutOfRange, V::OutsideScene, "a radius of -0 at the same centre (a zero radius)");
  add(0, 0, 0, 1, P::OutOfRange, V::OutsideScene, "a zero radius at the same centre");
  add(0, 2e6, 1.5, 1, P::OutOfRange, V::OutsideScene, "a radius above 1e6 m");
  add(2e6, 1, 2e6 + 1.5, 1, P::OutOfRange, V::OutsideScene, "centres beyond 1e6 m (a contact in every format)");
  add(3e19, 1, 3e19, 1, P::OutOfRange, V::OutsideScene, "centres whose binary32 squares would overflow");
  add(3e19, 1, -3e19, 1, P::OutOfRange, V::OutsideScene, "centres apart by 6e19 m: binary32's square overflows");
  return b;
}

}  // namespace collide::test
