#include "collide/simd_backend.hpp"

#include <stdexcept>

#include "collide/simd_kernel.hpp"

namespace collide {

SimdBackend::SimdBackend(LinkFormat format) : format_(format) {
  if (format != LinkFormat::Binary32 && format != LinkFormat::Binary64)
    throw std::invalid_argument(std::string("simd backend: no CPU kernel for ") + toString(format) +
                                " (binary32: simd, binary64: simd64)");
}

void SimdBackend::collide(const SphereTable& s, const PairList& pairs, ContactSet& out) {
  const std::size_t n = pairs.size();
  out.resizeForOverwrite(n);  // the kernel writes every entry
  out.format = format_;
  const SpheresF64 table{s.x.data(), s.y.data(), s.z.data(), s.r.data()};
  const ContactsF64 to{out.px.data(), out.py.data(), out.pz.data(), out.nx.data(), out.ny.data(),
                       out.nz.data(), out.depth.data(), out.hit.data()};
  if (format_ == LinkFormat::Binary64) gatherCollideF64(n, table, pairs.i.data(), pairs.j.data(), to);
  else gatherCollideF32(n, table, pairs.i.data(), pairs.j.data(), to);
  out.flags.clear();  // not computed on the hot path: setCpuRecordFlags when wanted
}

}  // namespace collide
