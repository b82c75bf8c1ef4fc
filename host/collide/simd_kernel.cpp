#include "collide/simd_kernel.hpp"

#include <cmath>

namespace collide {

// Reference semantics (ODE 0.16 dCollideSpheres, ode/src/collision_util.cpp; docs/scpu.md, "Semantics"):
//   d = sqrt(dx*dx + dy*dy + dz*dz), (dx,dy,dz) = p1 - p2, summed left to right
//   d > r1 + r2: no contact   (so a NaN d IS a contact, as in ODE)
//   d <= 0: pos p1, normal (1,0,0), depth r1 + r2
//   else inv = 1/d; normal = (p1-p2)*inv; k = 0.5*(r2 - r1 - d); pos = p1 + normal*k;
//        depth = r1 + r2 - d
// Both branches are computed and selected, which is what lets the loop vectorize;
// the division by d = 0 on the coincident path is computed and discarded.
namespace {
// The loop, for binary32 and binary64 alike. Always inlined into the two kernels below, whose
// restrict-qualified *parameters* it takes: GCC honours restrict there (not on local copies),
// which spares the vectorizer ~90 run-time alias checks it would otherwise give up on.
template <typename T>
__attribute__((always_inline)) inline void body(std::size_t n, const T* __restrict x1, const T* __restrict y1,
                                                const T* __restrict z1, const T* __restrict r1, const T* __restrict x2,
                                                const T* __restrict y2, const T* __restrict z2, const T* __restrict r2,
                                                T* __restrict px, T* __restrict py, T* __restrict pz, T* __restrict nx,
                                                T* __restrict ny, T* __restrict nz, T* __restrict depth,
                                                std::uint8_t* __restrict hit) {
  const T zero = 0, one = 1, half = 0.5;
  for (std::size_t k = 0; k < n; ++k) {
    const T dx = x1[k] - x2[k];
    const T dy = y1[k] - y2[k];
    const T dz = z1[k] - z2[k];
    const T d = std::sqrt(dx * dx + dy * dy + dz * dz);
    const T rsum = r1[k] + r2[k];
    const bool h = !(d > rsum);
    const bool coincident = d <= zero;
    const T inv = one / d;
    const T ex = dx * inv, ey = dy * inv, ez = dz * inv;
    const T kk = half * (r2[k] - r1[k] - d);
    const T cx = x1[k] + ex * kk, cy = y1[k] + ey * kk, cz = z1[k] + ez * kk;
    const T dep = rsum - d;

    const T sx = coincident ? x1[k] : cx;
    const T sy = coincident ? y1[k] : cy;
    const T sz = coincident ? z1[k] : cz;
    const T tx = coincident ? one : ex;
    const T ty = coincident ? zero : ey;
    const T tz = coincident ? zero : ez;
    const T sd = coincident ? rsum : dep;

    px[k] = h ? sx : zero;
    py[k] = h ? sy : zero;
    pz[k] = h ? sz : zero;
    nx[k] = h ? tx : zero;
    ny[k] = h ? ty : zero;
    nz[k] = h ? tz : zero;
    depth[k] = h ? sd : zero;
    hit[k] = h ? 1 : 0;
  }
}

// target_clones: one copy per ISA, picked at load time (AVX-512: 16 binary32 or 8 binary64
// pairs an instruction). Every copy is the same IEEE arithmetic (no contraction, sqrt and
// division correctly rounded in each ISA), so the results are bit-identical across them.
// Not inlined into their callers: restrict on a caller's local arrays is lost, and the
// vectorizer gives up. Two plain overloads, not a template: Clang's target_clones takes no
// function templates (llvm-project issue 116501), so the loop is a template and these are not.
__attribute__((noinline, target_clones("avx512f", "avx2", "default")))
void kernel(std::size_t n, const float* __restrict x1, const float* __restrict y1,
            const float* __restrict z1, const float* __restrict r1, const float* __restrict x2,
            const float* __restrict y2, const float* __restrict z2, const float* __restrict r2,
            float* __restrict px, float* __restrict py, float* __restrict pz, float* __restrict nx,
            float* __restrict ny, float* __restrict nz, float* __restrict depth,
            std::uint8_t* __restrict hit) {
  body(n, x1, y1, z1, r1, x2, y2, z2, r2, px, py, pz, nx, ny, nz, depth, hit);
}

__attribute__((noinline, target_clones("avx512f", "avx2", "default")))
void kernel(std::size_t n, const double* __restrict x1, const double* __restrict y1,
            const double* __restrict z1, const double* __restrict r1, const double* __restrict x2,
            const double* __restrict y2, const double* __restrict z2, const double* __restrict r2,
            double* __restrict px, double* __restrict py, double* __restrict pz, double* __restrict nx,
            double* __restrict ny, double* __restrict nz, double* __restrict depth,
            std::uint8_t* __restrict hit) {
  body(n, x1, y1, z1, r1, x2, y2, z2, r2, px, py, pz, nx, ny, nz, depth, hit);
}

constexpr std::size_t kBlock = 256;  // pairs a gather/kernel/widen round: ~15 kB of scratch

}  // namespace

// target_clones: one copy per ISA, picked at load time (AVX-512: 16 pairs an instruction,
// with hardware gathers). Every copy is the same IEEE binary32 arithmetic (no contraction;
// sqrt and division correctly rounded in each ISA), so results are bit-identical across them.
__attribute__((target_clones("avx512f", "avx2", "default")))
void gatherCollideF32(std::size_t n, const SpheresF64& s, const std::uint32_t* i, const std::uint32_t* j,
                      const ContactsF64& out) {
  alignas(64) float in[8][kBlock];
  alignas(64) float res[7][kBlock];
  alignas(64) std::uint8_t hit[kBlock];
  double* const dst[7] = {out.px, out.py, out.pz, out.nx, out.ny, out.nz, out.depth};
  for (std::size_t b0 = 0; b0 < n; b0 += kBlock) {
    const std::size_t m = n - b0 < kBlock ? n - b0 : kBlock;
    const std::uint32_t* bi = i + b0;
    const std::uint32_t* bj = j + b0;
    for (std::size_t k = 0; k < m; ++k) {
      in[0][k] = static_cast<float>(s.x[bi[k]]); in[1][k] = static_cast<float>(s.y[bi[k]]);
      in[2][k] = static_cast<float>(s.z[bi[k]]); in[3][k] = static_cast<float>(s.r[bi[k]]);
      in[4][k] = static_cast<float>(s.x[bj[k]]); in[5][k] = static_cast<float>(s.y[bj[k]]);
      in[6][k] = static_cast<float>(s.z[bj[k]]); in[7][k] = static_cast<float>(s.r[bj[k]]);
    }
    kernel(m, in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7], res[0], res[1], res[2], res[3], res[4],
           res[5], res[6], hit);
    for (int c = 0; c < 7; ++c) {
      double* d = dst[c] + b0;
      for (std::size_t k = 0; k < m; ++k) d[k] = res[c][k];
    }
    for (std::size_t k = 0; k < m; ++k) out.hit[b0 + k] = hit[k];
  }
}

// The binary64 twin: the gather copies (no rounding), the kernel writes the outputs in place.
__attribute__((target_clones("avx512f", "avx2", "default")))
void gatherCollideF64(std::size_t n, const SpheresF64& s, const std::uint32_t* i, const std::uint32_t* j,
                      const ContactsF64& out) {
  alignas(64) double in[8][kBlock];
  for (std::size_t b0 = 0; b0 < n; b0 += kBlock) {
    const std::size_t m = n - b0 < kBlock ? n - b0 : kBlock;
    const std::uint32_t* bi = i + b0;
    const std::uint32_t* bj = j + b0;
    for (std::size_t k = 0; k < m; ++k) {
      in[0][k] = s.x[bi[k]]; in[1][k] = s.y[bi[k]]; in[2][k] = s.z[bi[k]]; in[3][k] = s.r[bi[k]];
      in[4][k] = s.x[bj[k]]; in[5][k] = s.y[bj[k]]; in[6][k] = s.z[bj[k]]; in[7][k] = s.r[bj[k]];
    }
    kernel(m, in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7], out.px + b0, out.py + b0, out.pz + b0,
           out.nx + b0, out.ny + b0, out.nz + b0, out.depth + b0, out.hit + b0);
  }
}

void collideSpheresF64(std::size_t n, const PairsF64& in, const ContactsF64& out) {
  kernel(n, in.x1, in.y1, in.z1, in.r1, in.x2, in.y2, in.z2, in.r2, out.px, out.py, out.pz, out.nx,
         out.ny, out.nz, out.depth, out.hit);
}

void collideSpheresF32(std::size_t n, const PairsF32& in, const ContactsF32& out) {
  kernel(n, in.x1, in.y1, in.z1, in.r1, in.x2, in.y2, in.z2, in.r2, out.px, out.py, out.pz, out.nx,
         out.ny, out.nz, out.depth, out.hit);
}

}  // namespace collide
