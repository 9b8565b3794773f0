// The sphere kernel in AVX-512 lanes: eight contacts at a time (sphere_kernel.hpp says
// why, and how the bits stay the scalar pass's). Built with -mavx512f and without FMA contraction
// (-ffp-contract=off) (engine/CMakeLists.txt); called only on a CPU that has AVX-512F.
#include <immintrin.h>

#include <cstdint>

namespace ballast {
namespace {

constexpr int kLanes = 8;
using vd = double __attribute__((vector_size(64)));
using vm = long __attribute__((vector_size(64)));  // a lane mask: all bits set or clear

[[gnu::always_inline]] inline vd splat(double x) {
  return vd{x, x, x, x, x, x, x, x};
}
[[gnu::always_inline]] inline vd vsqrt(vd x) {
  // The masked form with every lane on: the same instruction, without GCC 12's false
  // "may be used uninitialized" about _mm512_sqrt_pd's undefined pass-through.
  return _mm512_mask_sqrt_pd(x, 0xFF, x);
}
[[gnu::always_inline]] inline int lane_bits(vm m) {
  return _mm512_movepi64_mask(reinterpret_cast<__m512i>(m));
}
[[gnu::always_inline]] inline bool any(vm m) {
  return lane_bits(m) != 0;
}
// One double per lane: p[index[k]·stride + offset]. Loads and inserts: on the Zen 4
// VM, vgatherdpd made the pass slower (docs/PERFORMANCE.md).
[[gnu::always_inline]] inline vd lanes(const double* p, const std::int32_t* index, long stride,
                                       long offset) {
  return _mm512_set_pd(p[index[7] * stride + offset], p[index[6] * stride + offset],
                       p[index[5] * stride + offset], p[index[4] * stride + offset],
                       p[index[3] * stride + offset], p[index[2] * stride + offset],
                       p[index[1] * stride + offset], p[index[0] * stride + offset]);
}

}  // namespace
}  // namespace ballast

#include "engine/sphere_kernel_lanes.hpp"

void ballast::sphere_kernel_ball_ball_avx512(const SphereKernelView& v, std::int32_t lo,
                                             std::int32_t hi) {
  ball_ball_contacts(v, lo, hi);
}
