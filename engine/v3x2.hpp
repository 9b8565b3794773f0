// Two V3s at once: lane 0 and lane 1 of SSE2 registers (part of the baseline x86-64
// instruction set, so no dispatch and no build flag). The sphere contact pass
// (forces.cpp) evaluates two contacts of one ball side by side with these.
//
// Every operation is the same IEEE operation as its scalar counterpart in v3.hpp,
// applied lane by lane, in the same order (dot = (x·x + y·y) + z·z), so a lane gives
// the bits the scalar code gives; -ffp-contract=off keeps them unfused. Branches of
// the scalar law become selects: the lane computes both sides and keeps one.
#pragma once

#include <emmintrin.h>

#include "engine/v3.hpp"

namespace ballast {

struct D2 {
  __m128d v;
};

[[gnu::always_inline]] inline D2 splat(double s) {
  return {_mm_set1_pd(s)};
}
// Lane 0 from a, lane 1 from b.
[[gnu::always_inline]] inline D2 lanes(double a, double b) {
  return {_mm_set_pd(b, a)};
}
[[gnu::always_inline]] inline D2 lanes(const double* a, const double* b) {
  return {_mm_loadh_pd(_mm_load_sd(a), b)};
}
[[gnu::always_inline]] inline double lane0(D2 a) {
  return _mm_cvtsd_f64(a.v);
}
[[gnu::always_inline]] inline double lane1(D2 a) {
  return _mm_cvtsd_f64(_mm_unpackhi_pd(a.v, a.v));
}
[[gnu::always_inline]] inline D2 operator+(D2 a, D2 b) {
  return {_mm_add_pd(a.v, b.v)};
}
[[gnu::always_inline]] inline D2 operator-(D2 a, D2 b) {
  return {_mm_sub_pd(a.v, b.v)};
}
[[gnu::always_inline]] inline D2 operator*(D2 a, D2 b) {
  return {_mm_mul_pd(a.v, b.v)};
}
[[gnu::always_inline]] inline D2 operator/(D2 a, D2 b) {
  return {_mm_div_pd(a.v, b.v)};
}
[[gnu::always_inline]] inline D2 operator-(D2 a) {  // exact, as scalar negation
  return {_mm_xor_pd(a.v, _mm_set1_pd(-0.0))};
}
[[gnu::always_inline]] inline D2 sqrt(D2 a) {
  return {_mm_sqrt_pd(a.v)};
}
// Lane masks (all bits set where true) and selects.
struct M2 {
  __m128d v;
};
[[gnu::always_inline]] inline M2 operator>(D2 a, D2 b) {
  return {_mm_cmpgt_pd(a.v, b.v)};
}
[[gnu::always_inline]] inline M2 operator&(M2 a, M2 b) {
  return {_mm_and_pd(a.v, b.v)};
}
[[gnu::always_inline]] inline int bits(M2 m) {  // bit k: lane k true
  return _mm_movemask_pd(m.v);
}
[[gnu::always_inline]] inline D2 select(M2 m, D2 yes, D2 no) {
  return {_mm_or_pd(_mm_and_pd(m.v, yes.v), _mm_andnot_pd(m.v, no.v))};
}

struct V3x2 {
  D2 x, y, z;
};

// Lane 0 from a, lane 1 from b.
[[gnu::always_inline]] inline V3x2 lanes(const Vec3& a, const Vec3& b) {
  return {lanes(&a[0], &b[0]), lanes(&a[1], &b[1]), lanes(&a[2], &b[2])};
}
[[gnu::always_inline]] inline V3x2 splat(const V3& a) {
  return {splat(a.x), splat(a.y), splat(a.z)};
}
[[gnu::always_inline]] inline V3 lane0(const V3x2& a) {
  return {lane0(a.x), lane0(a.y), lane0(a.z)};
}
[[gnu::always_inline]] inline V3 lane1(const V3x2& a) {
  return {lane1(a.x), lane1(a.y), lane1(a.z)};
}
// Lane 0 into a, lane 1 into b.
[[gnu::always_inline]] inline void store_lanes(Vec3& a, Vec3& b, const V3x2& v) {
  _mm_storel_pd(&a[0], v.x.v);
  _mm_storeh_pd(&b[0], v.x.v);
  _mm_storel_pd(&a[1], v.y.v);
  _mm_storeh_pd(&b[1], v.y.v);
  _mm_storel_pd(&a[2], v.z.v);
  _mm_storeh_pd(&b[2], v.z.v);
}
[[gnu::always_inline]] inline V3x2 operator+(const V3x2& a, const V3x2& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
[[gnu::always_inline]] inline V3x2 operator-(const V3x2& a, const V3x2& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
[[gnu::always_inline]] inline V3x2 operator-(const V3x2& a) {
  return {-a.x, -a.y, -a.z};
}
[[gnu::always_inline]] inline V3x2 operator*(D2 s, const V3x2& a) {
  return {s * a.x, s * a.y, s * a.z};
}
[[gnu::always_inline]] inline D2 dot(const V3x2& a, const V3x2& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
[[gnu::always_inline]] inline V3x2 cross(const V3x2& a, const V3x2& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace ballast
