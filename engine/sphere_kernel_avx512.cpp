// The sphere kernels in AVX-512 lanes: eight contacts, or eight spheres, at a time
// (sphere_kernel.hpp says why, and how the bits stay the scalar code's). Built with
// -mavx512f -mavx512dq and -ffp-contract=off, so nothing is fused into an FMA
// (engine/CMakeLists.txt); called only on a CPU with AVX-512F and DQ.
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
[[gnu::always_inline]] inline vd loadu(const double* p) {
  return _mm512_loadu_pd(p);
}
[[gnu::always_inline]] inline void storeu(double* p, vd x) {
  _mm512_storeu_pd(p, x);
}
[[gnu::always_inline]] inline __m256d quarter(vd x, int g) {
  // Zero-masked with every lane on: the plain form trips GCC 12's false "may be used
  // uninitialized" about its undefined pass-through, as vsqrt's does.
  return g == 0 ? _mm512_maskz_extractf64x4_pd(0xF, x, 0) : _mm512_maskz_extractf64x4_pd(0xF, x, 1);
}

}  // namespace
}  // namespace ballast

#include "engine/sphere_lane_ops.hpp"

namespace ballast {
namespace {

// Two-source permutes: index k < 8 takes a[k], 8 + k takes b[k].
[[gnu::always_inline]] inline vd permute(vd a, __m512i index, vd b) {
  return _mm512_permutex2var_pd(a, index, b);
}
#define BALLAST_IX(e0, e1, e2, e3, e4, e5, e6, e7) _mm512_set_epi64(e7, e6, e5, e4, e3, e2, e1, e0)

// Eight consecutive three-vectors (24 doubles in three registers) into lanes: two
// permutes per component (and their inverse for the store).
[[gnu::always_inline]] inline L3 load_aos3(const double* p) {
  const vd a = loadu(p), b = loadu(p + 8), c = loadu(p + 16);
  const vd x = permute(a, BALLAST_IX(0, 3, 6, 9, 12, 15, 0, 0), b);
  const vd y = permute(a, BALLAST_IX(1, 4, 7, 10, 13, 0, 0, 0), b);
  const vd z = permute(a, BALLAST_IX(2, 5, 8, 11, 14, 0, 0, 0), b);
  return {permute(x, BALLAST_IX(0, 1, 2, 3, 4, 5, 10, 13), c),
          permute(y, BALLAST_IX(0, 1, 2, 3, 4, 8, 11, 14), c),
          permute(z, BALLAST_IX(0, 1, 2, 3, 4, 9, 12, 15), c)};
}
[[gnu::always_inline]] inline void store_aos3(double* p, const L3& v) {
  const vd xy0 = permute(v.x, BALLAST_IX(0, 8, 0, 1, 9, 0, 2, 10), v.y);
  const vd xy1 = permute(v.x, BALLAST_IX(0, 3, 11, 0, 4, 12, 0, 5), v.y);
  const vd xy2 = permute(v.x, BALLAST_IX(13, 0, 6, 14, 0, 7, 15, 0), v.y);
  storeu(p, permute(xy0, BALLAST_IX(0, 1, 8, 3, 4, 9, 6, 7), v.z));
  storeu(p + 8, permute(xy1, BALLAST_IX(10, 1, 2, 11, 4, 5, 12, 7), v.z));
  storeu(p + 16, permute(xy2, BALLAST_IX(0, 13, 2, 3, 14, 5, 6, 15), v.z));
}
#undef BALLAST_IX

}  // namespace
}  // namespace ballast

#include "engine/sphere_kernel_lanes.hpp"
#include "engine/sphere_update_lanes.hpp"
#include "engine/sphere_wall_lanes.hpp"

void ballast::sphere_kernel_ball_ball_avx512(const SphereKernelView& v, std::int32_t lo,
                                             std::int32_t hi) {
  ball_ball_contacts(v, lo, hi);
}

void ballast::sphere_kernel_ball_plane_avx512(const SpherePlaneView& v, std::int32_t first,
                                              std::int32_t last) {
  ball_plane_contacts(v, first, last);
}

std::int32_t ballast::sphere_kernel_update_avx512(const SphereUpdateView& v, std::int32_t lo,
                                                  std::int32_t hi, SphereUpdateReport& report) {
  return update_contiguous_spheres(v, lo, hi, report);
}
