// The sphere kernel's contact body (sphere_kernel.hpp), lane-generic: included by
// one file per instruction set (sphere_lane_ops.hpp lists what that file defines).
#pragma once

#include <cstdint>

#include "engine/sphere_kernel.hpp"
#include "engine/sphere_lane_ops.hpp"
#include "engine/sphere_law_lanes.hpp"

namespace ballast {
namespace {

// The side-a wrench of the ball whose contacts the lanes are going through, carried
// from lane to lane and batch to batch. Each lane adds its wrench to it (starting
// again from zero at a new ball: 0 + F, as the scalar pass starts from zero) and
// stores the sum in the ball's a_side slot, which the ball's last lane leaves at its
// total. Stored, never reloaded: adding into a_side in memory made each lane wait
// for the store of the lane before (the hottest samples of a first version).
// Held as one lane's wrench (columns4 / columns2), so a lane adds it in two
// instructions.
struct RunningWrench {
  std::int32_t ball = -1;
  __m256d force_torque_x = _mm256_setzero_pd();  // fx fy fz tx
  __m128d torque_yz = _mm_setzero_pd();          // ty tz
};

// Contacts cc[0..kLanes) of side-a balls ia[...] (in contact order); the first n
// are real, the others repeat one of them and are not stored.
template <bool kFriction, bool kOneMaterial>
[[gnu::always_inline]] inline void batch(const SphereKernelView& v, const std::int32_t* ia,
                                         const std::int32_t* cc, int n, RunningWrench& run) {
  std::int32_t jb[kLanes];
  for (int k = 0; k < kLanes; ++k) jb[k] = v.b[cc[k]];
  const L3 xi = load3(v.position, ia), xj = load3(v.position, jb);
  const vd ri = lanes(v.radius, ia, 1, 0), rj = lanes(v.radius, jb, 1, 0);
  const L3 d = xi - xj;
  const vd dist2 = dot(d, d);
  const vd reach = ri + rj;
  // Touching unless dist2 >= reach²: a NaN distance counts as touching, as in the
  // scalar test, so that a blow-up reaches the integrator's check.
  const vm touch = ~(dist2 >= reach * reach);
  const vd dist = vsqrt(dist2);
  const L3 normal = (splat(1.0) / dist) * d;  // from j towards i
  const vd overlap = reach - dist;
  const vd li = ri - splat(0.5) * overlap, lj = rj - splat(0.5) * overlap;
  // Both lever arms lie along the normal: one cross product for the spin velocity.
  const L3 vrel =
      (load3(v.velocity, ia) - load3(v.velocity, jb)) -
      cross(li * load3(v.angular_velocity, ia) + lj * load3(v.angular_velocity, jb), normal);
  vd kn, ks, mu;
  if constexpr (kOneMaterial) {
    kn = splat(v.pair[0]);
    ks = splat(v.pair[1]);
    mu = splat(v.pair[2]);
  } else {
    std::int32_t pair[kLanes];
    for (int k = 0; k < kLanes; ++k) pair[k] = v.material[ia[k]] * v.materials + v.material[jb[k]];
    kn = lanes(v.pair, pair, 3, 0);
    ks = lanes(v.pair, pair, 3, 1);
    mu = lanes(v.pair, pair, 3, 2);
  }
  const vd fn = kn * overlap;
  const vd zero = splat(0.0);
  const L3 s0 = kFriction ? load3(v.shear_force, cc) : L3{zero, zero, zero};
  const LawLanes law = linear_law<kFriction>(normal, vrel, fn, ks, mu, v.dt, touch, s0);
  const L3 f = law.force;
  L3 s = law.shear;
  const vd slip = law.slip;
  const int sliding_lanes = law.sliding_lanes;
  // An open contact stores zeros (forces.cpp open_contact): +0, which adds nothing.
  const L3 o{zero, zero, zero};
  const L3 fa = select(touch, f, o), fb = select(touch, -f, o);
  // Without friction the force passes through both centres: zero torque, as the
  // scalar pass stores it (forces.cpp ball_ball).
  L3 ta = o, tb = o;
  if constexpr (kFriction) {
    const L3 nxf = cross(normal, f);
    ta = select(touch, (-li) * nxf, o);
    tb = select(touch, (-lj) * nxf, o);
  }
  s = select(touch, s, o);
  // Each lane's values side by side, four lanes at a time (a transpose of the rows),
  // so that a lane stores its wrenches and shear force a register at a time.
  const int touching = lane_bits(touch);
  const vd fn_stored = select(touch, fn, zero);
  for (int g = 0; 4 * g < n; ++g) {
    __m256d a_ft[4], b_ft[4], shear_fn[4];
    __m128d a_t[4], b_t[4];
    columns4(fa.x, fa.y, fa.z, ta.x, g, a_ft);
    columns2(ta.y, ta.z, g, a_t);
    columns4(fb.x, fb.y, fb.z, tb.x, g, b_ft);
    columns2(tb.y, tb.z, g, b_t);
    columns4(s.x, s.y, s.z, fn_stored, g, shear_fn);
    for (int q = 0; q < 4 && 4 * g + q < n; ++q) {
      const int k = 4 * g + q;
      const long c = cc[k];
      v.active[c] = std::uint8_t((touching >> k) & 1);
      const __m128d sz_fn = _mm256_extractf128_pd(shear_fn[q], 1);
      _mm_storeh_pd(v.normal_force + c, sz_fn);
      if constexpr (kFriction) {
        double* const sf = v.shear_force + 3 * c;
        _mm_storeu_pd(sf, _mm256_castpd256_pd128(shear_fn[q]));
        _mm_store_sd(sf + 2, sz_fn);
      }
      double* const bw = v.b_wrench + 6 * c;
      _mm256_storeu_pd(bw, b_ft[q]);
      _mm_storeu_pd(bw + 4, b_t[q]);
      const std::int32_t i = ia[k];
      // All ones for the same ball as the lane before: its sum carries on; from zero
      // otherwise (0 + F, as the scalar pass starts from zero).
      const __m256i keep = _mm256_set1_epi64x(-std::int64_t(i == run.ball));
      run.force_torque_x =
          _mm256_add_pd(_mm256_and_pd(run.force_torque_x, _mm256_castsi256_pd(keep)), a_ft[q]);
      run.torque_yz = _mm_add_pd(
          _mm_and_pd(run.torque_yz, _mm_castsi128_pd(_mm256_castsi256_si128(keep))), a_t[q]);
      double* const aw = v.a_side + 6 * long(i);
      _mm256_storeu_pd(aw, run.force_torque_x);
      _mm_storeu_pd(aw + 4, run.torque_yz);
      run.ball = i;
    }
  }
  // Slip work, only where a lane slid (rare once a bed settles): touching slip_total
  // for every contact would pull its cache lines in every step.
  if constexpr (kFriction) {
    if (sliding_lanes != 0 && v.slip_total != nullptr)
      for (int k = 0; k < n; ++k)
        if ((sliding_lanes >> k) & 1) v.slip_total[cc[k]] += slip[k];
  }
}

template <bool kFriction, bool kOneMaterial>
void ball_ball(const SphereKernelView& view, std::int32_t lo, std::int32_t hi) {
  // A local copy: the stores into `active` (a char type, which may alias anything)
  // would otherwise make the compiler reload every pointer of the view after each.
  const SphereKernelView v = view;
  // A ball with no live contact gets no lane: its side-a wrench is zero.
  for (long q = 6L * lo; q < 6L * hi; ++q) v.a_side[q] = 0.0;
  const std::int32_t end = v.flat_first[hi];
  std::int32_t k = v.flat_first[lo];
  RunningWrench run;
  for (; k + kLanes <= end; k += kLanes)
    batch<kFriction, kOneMaterial>(v, v.flat_a + k, v.flat_c + k, kLanes, run);
  if (k < end) {
    alignas(64) std::int32_t ia[kLanes], cc[kLanes];
    const int n = end - k;
    for (int q = 0; q < kLanes; ++q)
      ia[q] = v.flat_a[k + (q < n ? q : 0)], cc[q] = v.flat_c[k + (q < n ? q : 0)];
    batch<kFriction, kOneMaterial>(v, ia, cc, n, run);
  }
}

// The contact kernel for this instruction set: friction and a one-material scene are
// template arguments, so that neither costs a test per contact.
void ball_ball_contacts(const SphereKernelView& v, std::int32_t lo, std::int32_t hi) {
  const bool one = v.materials == 1;
  if (v.shear_force != nullptr)
    one ? ball_ball<true, true>(v, lo, hi) : ball_ball<true, false>(v, lo, hi);
  else
    one ? ball_ball<false, true>(v, lo, hi) : ball_ball<false, false>(v, lo, hi);
}

}  // namespace
}  // namespace ballast
