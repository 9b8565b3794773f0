// A plain three-double vector for the innermost loops (contact laws, force loop,
// gather). Eigen's fixed-size Vector3d vectorises as one 2-lane packet plus one
// scalar under the baseline x86-64 instruction set, and the shuffles between them
// cost more than they save: the contact loop ran 15 % more instructions than with
// this struct, which the compiler keeps in scalar registers. Everything outside the
// hot loops uses Eigen (types.hpp); load()/store() convert, bit for bit.
#pragma once

#include "engine/types.hpp"

namespace ballast {

struct V3 {
  double x, y, z;
};

[[gnu::always_inline]] inline V3 load(const Vec3& v) {
  return {v[0], v[1], v[2]};
}
[[gnu::always_inline]] inline void store(Vec3& out, const V3& v) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

[[gnu::always_inline]] inline V3 operator+(const V3& a, const V3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
[[gnu::always_inline]] inline V3 operator-(const V3& a, const V3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
[[gnu::always_inline]] inline V3 operator-(const V3& a) {
  return {-a.x, -a.y, -a.z};
}
[[gnu::always_inline]] inline V3 operator*(double s, const V3& a) {
  return {s * a.x, s * a.y, s * a.z};
}
[[gnu::always_inline]] inline V3& operator+=(V3& a, const V3& b) {
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
[[gnu::always_inline]] inline double dot(const V3& a, const V3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
[[gnu::always_inline]] inline V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace ballast
