// The sphere kernels in AVX2 lanes: four contacts, or four spheres, at a time
// (sphere_kernel.hpp says why, and how the bits stay the scalar code's). Built with
// -mavx2 and without FMA (engine/CMakeLists.txt); called only on a CPU with AVX2.
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
[[gnu::always_inline]] inline vd loadu(const double* p) {
  return _mm256_loadu_pd(p);
}
[[gnu::always_inline]] inline void storeu(double* p, vd x) {
  _mm256_storeu_pd(p, x);
}
[[gnu::always_inline]] inline __m256d quarter(vd x, int /*g: 0*/) {
  return x;
}

}  // namespace
}  // namespace ballast

#include "engine/sphere_lane_ops.hpp"

namespace ballast {
namespace {

// Four consecutive three-vectors, x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3, into
// lanes: three loads and six shuffles (and their inverse for the store).
[[gnu::always_inline]] inline L3 load_aos3(const double* p) {
  const vd a = loadu(p), b = loadu(p + 4), c = loadu(p + 8);
  const vd t0 = _mm256_permute2f128_pd(a, b, 0x30);  // x0 y0 | x2 y2
  const vd t1 = _mm256_permute2f128_pd(a, c, 0x21);  // z0 x1 | z2 x3
  const vd t2 = _mm256_permute2f128_pd(b, c, 0x30);  // y1 z1 | y3 z3
  return {_mm256_shuffle_pd(t0, t1, 0b1010), _mm256_shuffle_pd(t0, t2, 0b0101),
          _mm256_shuffle_pd(t1, t2, 0b1010)};
}
[[gnu::always_inline]] inline void store_aos3(double* p, const L3& v) {
  const vd t0 = _mm256_shuffle_pd(v.x, v.y, 0b0000);  // x0 y0 | x2 y2
  const vd t1 = _mm256_shuffle_pd(v.z, v.x, 0b1010);  // z0 x1 | z2 x3
  const vd t2 = _mm256_shuffle_pd(v.y, v.z, 0b1111);  // y1 z1 | y3 z3
  storeu(p, _mm256_permute2f128_pd(t0, t1, 0x20));
  storeu(p + 4, _mm256_permute2f128_pd(t2, t0, 0x30));
  storeu(p + 8, _mm256_permute2f128_pd(t1, t2, 0x31));
}

}  // namespace
}  // namespace ballast

#include "engine/sphere_kernel_lanes.hpp"
#include "engine/sphere_update_lanes.hpp"
#include "engine/sphere_wall_lanes.hpp"

void ballast::sphere_kernel_ball_ball_avx2(const SphereKernelView& v, std::int32_t lo,
                                           std::int32_t hi) {
  ball_ball_contacts(v, lo, hi);
}

void ballast::sphere_kernel_ball_plane_avx2(const SpherePlaneView& v, std::int32_t first,
                                            std::int32_t last) {
  ball_plane_contacts(v, first, last);
}

std::int32_t ballast::sphere_kernel_update_avx2(const SphereUpdateView& v, std::int32_t lo,
                                                std::int32_t hi, SphereUpdateReport& report) {
  return update_contiguous_spheres(v, lo, hi, report);
}
