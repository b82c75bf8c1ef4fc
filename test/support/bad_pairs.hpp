#pragma once
// Pairs of every kind the input policy rejects, with a good contact first (test only).
#include <limits>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "collide/input_policy.hpp"

namespace collide::test {

struct BadPairs {
  SphereTable spheres;
  PairList pairs;
  std::vector<PairInput> want;
  std::vector<std::string> what;
};

inline BadPairs badPairs() {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  BadPairs b;
  auto add = [&](double x1, double r1, double x2, double r2, PairInput w, const std::string& what) {
    const auto i = static_cast<std::uint32_t>(b.spheres.size());
    b.spheres.push(x1, 0.5, 0, r1);
    b.spheres.push(x2, 0.5, 0, r2);
    b.pairs.push(i, i + 1);
    b.want.push_back(w);
    b.what.push_back(what);
  };
  add(0, 1, 1.5, 1, PairInput::Ok, "an ordinary contact");
  add(nan, 1, 1.5, 1, PairInput::NonFinite, "a NaN coordinate");
  add(0, 1, inf, 1, PairInput::NonFinite, "an infinite coordinate");
  add(0, inf, 1.5, 1, PairInput::NonFinite, "an infinite radius (the SCPU calls it a contact with NaN fields)");
  add(0, nan, 1.5, 1, PairInput::NonFinite, "a NaN radius");
  add(0, -1, 1.5, 2, PairInput::OutOfRange, "a negative radius (r1 + r2 still covers the distance)");
  add(0, 0, 0, 1, PairInput::OutOfRange, "a zero radius at the same centre");
  add(0, 2e6, 1.5, 1, PairInput::OutOfRange, "a radius above 1e6 m");
  add(2e6, 1, 2e6 + 1.5, 1, PairInput::OutOfRange, "centres beyond 1e6 m (a contact in every format)");
  add(3e19, 1, 3e19, 1, PairInput::OutOfRange, "centres whose binary32 squares would overflow");
  return b;
}

}  // namespace collide::test
