// Arithmetic on lanes for the sphere kernels (sphere_kernel.hpp), shared by their
// lane-generic bodies (sphere_kernel_lanes.hpp: contacts, sphere_update_lanes.hpp:
// the leapfrog). Included by one file per instruction set after it defines, in an
// anonymous namespace of ballast: kLanes, vd (kLanes doubles), vm (the matching lane
// mask), splat, vsqrt, lane_bits, any, lanes (one double per lane from an index
// list), loadu and storeu (kLanes consecutive doubles); and after it, for the bodies
// that follow, load_aos3 and store_aos3 (kLanes consecutive three-vectors, x y z x
// y z ...), and quarter (the lanes 4g .. 4g + 3 of a vd as one AVX register).
// Everything here has internal linkage, so each file keeps its own
// instructions.
#pragma once

#include <immintrin.h>

#include <cstdint>

namespace ballast {
namespace {

// A three-vector per lane, with the scalar law's operations in the scalar order
// (v3.hpp): dot is (x·x + y·y) + z·z, cross is written out the same way.
struct L3 {
  vd x, y, z;
};
[[gnu::always_inline]] inline L3 load3(const double* p, const std::int32_t* index) {
  return {lanes(p, index, 3, 0), lanes(p, index, 3, 1), lanes(p, index, 3, 2)};
}
[[gnu::always_inline]] inline L3 operator+(const L3& a, const L3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
[[gnu::always_inline]] inline L3 operator-(const L3& a, const L3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
[[gnu::always_inline]] inline L3 operator-(const L3& a) {
  return {-a.x, -a.y, -a.z};
}
[[gnu::always_inline]] inline L3 operator*(vd s, const L3& a) {
  return {s * a.x, s * a.y, s * a.z};
}
[[gnu::always_inline]] inline vd dot(const L3& a, const L3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
[[gnu::always_inline]] inline L3 cross(const L3& a, const L3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
[[gnu::always_inline]] inline vd select(vm m, vd a, vd b) {
  return m ? a : b;
}
[[gnu::always_inline]] inline L3 select(vm m, const L3& a, const L3& b) {
  return {m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z};
}

// |x|, by clearing the sign bit: the same bits as std::abs.
[[gnu::always_inline]] inline vd vabs(vd x) {
  return reinterpret_cast<vd>(reinterpret_cast<vm>(x) & ~reinterpret_cast<vm>(splat(-0.0)));
}
// Finite: not infinite and not NaN (a NaN compares false).
[[gnu::always_inline]] inline vm finite(vd x) {
  return vabs(x) < splat(__builtin_inf());
}

// Lanes 4g .. 4g + 3 of four rows, as one register per lane holding that lane's four
// values (a 4 × 4 transpose): col[q] = {r0[4g + q], r1[...], r2[...], r3[...]}.
[[gnu::always_inline]] inline void columns4(vd r0, vd r1, vd r2, vd r3, int g, __m256d col[4]) {
  const __m256d a = quarter(r0, g), b = quarter(r1, g), c = quarter(r2, g), d = quarter(r3, g);
  const __m256d ab_even = _mm256_unpacklo_pd(a, b);  // a0 b0 | a2 b2
  const __m256d ab_odd = _mm256_unpackhi_pd(a, b);   // a1 b1 | a3 b3
  const __m256d cd_even = _mm256_unpacklo_pd(c, d);
  const __m256d cd_odd = _mm256_unpackhi_pd(c, d);
  col[0] = _mm256_permute2f128_pd(ab_even, cd_even, 0x20);  // a0 b0 c0 d0
  col[1] = _mm256_permute2f128_pd(ab_odd, cd_odd, 0x20);
  col[2] = _mm256_permute2f128_pd(ab_even, cd_even, 0x31);
  col[3] = _mm256_permute2f128_pd(ab_odd, cd_odd, 0x31);
}
// The same for two rows: col[q] = {r0[4g + q], r1[4g + q]}.
[[gnu::always_inline]] inline void columns2(vd r0, vd r1, int g, __m128d col[4]) {
  const __m256d a = quarter(r0, g), b = quarter(r1, g);
  const __m256d even = _mm256_unpacklo_pd(a, b);  // a0 b0 | a2 b2
  const __m256d odd = _mm256_unpackhi_pd(a, b);   // a1 b1 | a3 b3
  col[0] = _mm256_castpd256_pd128(even);
  col[1] = _mm256_castpd256_pd128(odd);
  col[2] = _mm256_extractf128_pd(even, 1);
  col[3] = _mm256_extractf128_pd(odd, 1);
}

}  // namespace
}  // namespace ballast
