// The sphere kernel in AVX2 lanes: four contacts at a time (sphere_kernel.hpp says
// why, and how the bits stay the scalar pass's). Built with -mavx2 and without FMA
// (engine/CMakeLists.txt); called only on a CPU that has AVX2.
#include <immintrin.h>

#include <cstdint>

namespace ballast {
namespace {

constexpr int kLanes = 4;
using vd = double __attribute__((vector_size(32)));
using vm = long __attribute__((vector_size(32)));  // a lane mask: all bits set or clear

[[gnu::always_inline]] inline vd splat(double x) {
  return vd{x, x, x, x};
}
[[gnu::always_inline]] inline vd vsqrt(vd x) {
  return _mm256_sqrt_pd(x);
}
[[gnu::always_inline]] inline int lane_bits(vm m) {
  return _mm256_movemask_pd(reinterpret_cast<__m256d>(m));
}
[[gnu::always_inline]] inline bool any(vm m) {
  return lane_bits(m) != 0;
}
// One double per lane: p[index[k]·stride + offset]. Loads and inserts: on the Zen 4
// VM, vgatherdpd made the pass slower (docs/PERFORMANCE.md).
[[gnu::always_inline]] inline vd lanes(const double* p, const std::int32_t* index, long stride,
                                       long offset) {
  return _mm256_set_pd(p[index[3] * stride + offset], p[index[2] * stride + offset],
                       p[index[1] * stride + offset], p[index[0] * stride + offset]);
}

}  // namespace
}  // namespace ballast

#include "engine/sphere_kernel_lanes.hpp"

void ballast::sphere_kernel_ball_ball_avx2(const SphereKernelView& v, std::int32_t lo,
                                           std::int32_t hi) {
  ball_ball_contacts(v, lo, hi);
}
