#include "collide/simd_backend.hpp"

#include "collide/simd_kernel.hpp"

namespace collide {

void SimdBackend::collide(const SphereTable& s, const PairList& pairs, ContactSet& out) {
  const std::size_t n = pairs.size();
  for (auto& v : in_) v.resize(n);
  for (auto& v : res_) v.resize(n);
  hit_.resize(n);
  // Gather: double -> float is one RNE rounding, the same conversion the AFU's link
  // carries (binary32 link format).
  for (std::size_t k = 0; k < n; ++k) {
    const auto a = pairs.i[k], b = pairs.j[k];
    in_[0][k] = static_cast<float>(s.x[a]); in_[1][k] = static_cast<float>(s.y[a]);
    in_[2][k] = static_cast<float>(s.z[a]); in_[3][k] = static_cast<float>(s.r[a]);
    in_[4][k] = static_cast<float>(s.x[b]); in_[5][k] = static_cast<float>(s.y[b]);
    in_[6][k] = static_cast<float>(s.z[b]); in_[7][k] = static_cast<float>(s.r[b]);
  }
  collideSpheresF32(n,
                    PairsF32{in_[0].data(), in_[1].data(), in_[2].data(), in_[3].data(),
                             in_[4].data(), in_[5].data(), in_[6].data(), in_[7].data()},
                    ContactsF32{res_[0].data(), res_[1].data(), res_[2].data(), res_[3].data(),
                                res_[4].data(), res_[5].data(), res_[6].data(), hit_.data()});
  out.resize(n);
  out.format = LinkFormat::Binary32;
  std::vector<double>* dst[7] = {&out.px, &out.py, &out.pz, &out.nx, &out.ny, &out.nz, &out.depth};
  for (int c = 0; c < 7; ++c)
    for (std::size_t k = 0; k < n; ++k) (*dst[c])[k] = res_[c][k];
  out.hit.assign(hit_.begin(), hit_.end());
}

}  // namespace collide
