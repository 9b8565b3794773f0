// The sphere kernel's ball–plane contacts (sphere_kernel.hpp, SpherePlaneView),
// lane-generic: included by one file per instruction set, after sphere_lane_ops.hpp's
// definitions. forces.cpp's ball_wall for a sphere against a plane, lane by lane, in
// the scalar order of operations, so that the bits are the scalar pass's.
//
// Why: in a box a good share of a sphere bed's contacts are with the walls, and once
// the ball–ball contacts ran in lanes the scalar wall pass was the step's next largest
// cost (docs/PERFORMANCE.md, "What bought what").
#pragma once

#include <cstdint>

#include "engine/sphere_kernel.hpp"
#include "engine/sphere_lane_ops.hpp"
#include "engine/sphere_law_lanes.hpp"

namespace ballast {
namespace {

// Candidates whose balls are ia[0..kLanes) and walls iw[...]; the first n are real,
// the others repeat the first and are not stored. kContiguous: the candidates are
// c0 .. c0 + kLanes, so their shear forces load as one block.
template <bool kFriction, bool kContiguous>
[[gnu::always_inline]] inline void plane_batch(const SpherePlaneView& v, const std::int32_t* ia,
                                               const std::int32_t* iw, std::int32_t c0, int n) {
  const L3 x = load3(v.position, ia);
  const vd r = lanes(v.radius, ia, 1, 0);
  const L3 normal{lanes(v.plane, iw, kPlaneRow, 0), lanes(v.plane, iw, kPlaneRow, 1),
                  lanes(v.plane, iw, kPlaneRow, 2)};
  const L3 on_plane{lanes(v.plane, iw, kPlaneRow, 3), lanes(v.plane, iw, kPlaneRow, 4),
                    lanes(v.plane, iw, kPlaneRow, 5)};
  const L3 wall_velocity{lanes(v.plane, iw, kPlaneRow, 6), lanes(v.plane, iw, kPlaneRow, 7),
                         lanes(v.plane, iw, kPlaneRow, 8)};
  const vd sd = dot(normal, x - on_plane);  // signed distance of the centre, m
  const vd overlap = r - sd;
  // Touching unless overlap <= 0: a NaN counts as touching, as in the scalar test.
  const vm touch = ~(overlap <= splat(0.0));
  const vd zero = splat(0.0);
  const L3 o{zero, zero, zero};
  L3 arm = o, vrel;
  if constexpr (kFriction) {
    // The lever arm from the body's centre to the contact point, as the scalar pass
    // forms it (for a sphere: −sd·n, up to rounding). A sphere's ball centre is a copy
    // of its body's (the integrator stores one into the other), so x serves for both.
    arm = (x - sd * normal) - x;
    vrel = (load3(v.velocity, ia) + cross(load3(v.angular_velocity, ia), arm)) - wall_velocity;
  } else {
    // A frictionless sphere: the force passes through its centre, no spin is read.
    vrel = load3(v.velocity, ia) - wall_velocity;
  }
  std::int32_t pair[kLanes];
  for (int k = 0; k < kLanes; ++k) pair[k] = v.material[ia[k]] * v.walls + iw[k];
  const vd fn = lanes(v.pair, pair, 3, 0) * overlap;
  L3 s0 = o;
  if constexpr (kFriction) {
    if constexpr (kContiguous) {
      s0 = load_aos3(v.shear_force + 3L * c0);
    } else {
      std::int32_t cc[kLanes];
      for (int k = 0; k < kLanes; ++k) cc[k] = c0 + (k < n ? k : 0);
      s0 = load3(v.shear_force, cc);
    }
  }
  const LawLanes law = linear_law<kFriction>(normal, vrel, fn, lanes(v.pair, pair, 3, 1),
                                             lanes(v.pair, pair, 3, 2), v.dt, touch, s0);
  // An open contact stores zeros (forces.cpp open_contact) and adds +0 to its ball,
  // which changes no bits: a ball's sum is never −0, as it starts from +0.
  const L3 f = select(touch, law.force, o), fb = select(touch, -law.force, o);
  L3 t = o, s = o;
  if constexpr (kFriction) {
    t = select(touch, cross(arm, law.force), o);
    s = select(touch, law.shear, o);
  }
  const vd fn_stored = select(touch, fn, zero);
  const int touching = lane_bits(touch);
  // Each lane's values side by side, four lanes at a time (ball_ball says why).
  for (int g = 0; 4 * g < n; ++g) {
    __m256d a_ft[4], b_f[4], shear_fn[4];
    __m128d a_t[4];
    columns4(f.x, f.y, f.z, t.x, g, a_ft);
    columns2(t.y, t.z, g, a_t);
    columns4(fb.x, fb.y, fb.z, zero, g, b_f);
    columns4(s.x, s.y, s.z, fn_stored, g, shear_fn);
    for (int q = 0; q < 4 && 4 * g + q < n; ++q) {
      const int k = 4 * g + q;
      if (!v.is_plane[iw[k]]) continue;  // a wall of another shape: the scalar pass's
      const long c = c0 + k;
      v.active[c] = std::uint8_t((touching >> k) & 1);
      const __m128d sz_fn = _mm256_extractf128_pd(shear_fn[q], 1);
      _mm_storeh_pd(v.normal_force + c, sz_fn);
      double* const bw = v.b_wrench + 6 * c;  // the force only: the torque stays zero
      _mm_storeu_pd(bw, _mm256_castpd256_pd128(b_f[q]));
      _mm_store_sd(bw + 2, _mm256_extractf128_pd(b_f[q], 1));
      double* const aw = v.a_side + 6 * long(ia[k]);
      if constexpr (kFriction) {
        _mm256_storeu_pd(aw, _mm256_add_pd(_mm256_loadu_pd(aw), a_ft[q]));
        _mm_storeu_pd(aw + 4, _mm_add_pd(_mm_loadu_pd(aw + 4), a_t[q]));
        double* const sf = v.shear_force + 3 * c;
        _mm_storeu_pd(sf, _mm256_castpd256_pd128(shear_fn[q]));
        _mm_store_sd(sf + 2, sz_fn);
        if (((law.sliding_lanes >> k) & 1) && v.slip_total != nullptr)
          v.slip_total[c] += law.slip[k];
      } else {
        // No torque: the force passes through the centre (the scalar pass adds none).
        const __m256d ft = _mm256_loadu_pd(aw);
        _mm256_storeu_pd(aw, _mm256_blend_pd(_mm256_add_pd(ft, a_ft[q]), ft, 0b1000));
      }
    }
  }
}

template <bool kFriction>
void ball_plane(const SpherePlaneView& view, std::int32_t first, std::int32_t last) {
  const SpherePlaneView v = view;  // a local copy: see ball_ball
  std::int32_t c = first;
  for (; c + kLanes <= last; c += kLanes)
    plane_batch<kFriction, true>(v, v.a + c, v.b + c, c, kLanes);
  if (c < last) {
    alignas(64) std::int32_t ia[kLanes], iw[kLanes];
    const int n = last - c;
    for (int q = 0; q < kLanes; ++q)
      ia[q] = v.a[c + (q < n ? q : 0)], iw[q] = v.b[c + (q < n ? q : 0)];
    plane_batch<kFriction, false>(v, ia, iw, c, n);
  }
}

void ball_plane_contacts(const SpherePlaneView& v, std::int32_t first, std::int32_t last) {
  if (v.shear_force != nullptr)
    ball_plane<true>(v, first, last);
  else
    ball_plane<false>(v, first, last);
}

}  // namespace
}  // namespace ballast
