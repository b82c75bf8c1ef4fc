#include "collide/simd_backend.hpp"

#include "collide/simd_kernel.hpp"

namespace collide {

void SimdBackend::collide(const SphereTable& s, const PairList& pairs, ContactSet& out) {
  const std::size_t n = pairs.size();
  out.resizeForOverwrite(n);  // the kernel writes every entry
  out.format = LinkFormat::Binary32;
  gatherCollideF32(n, SpheresF64{s.x.data(), s.y.data(), s.z.data(), s.r.data()}, pairs.i.data(), pairs.j.data(),
                   ContactsF64{out.px.data(), out.py.data(), out.pz.data(), out.nx.data(), out.ny.data(),
                               out.nz.data(), out.depth.data(), out.hit.data()});
  out.flags.clear();  // not computed on the hot path: setCpuRecordFlags when wanted
}

}  // namespace collide
