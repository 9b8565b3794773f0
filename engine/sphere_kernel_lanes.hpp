// The sphere kernel's contact body (sphere_kernel.hpp), lane-generic: included by
// one file per instruction set (sphere_lane_ops.hpp lists what that file defines).
#pragma once

#include <bit>
#include <cstdint>

#include "engine/sphere_kernel.hpp"
#include "engine/sphere_lane_ops.hpp"

namespace ballast {
namespace {

// What a batch hands back per lane, as rows of kLanes doubles: the scalar stores
// that follow read them lane by lane.
enum Row {
  kFx,
  kFy,
  kFz,
  kTax,
  kTay,
  kTaz,
  kBfx,
  kBfy,
  kBfz,
  kTbx,
  kTby,
  kTbz,
  kSx,
  kSy,
  kSz,
  kFn,
  kSlip,
  kRows
};

// The side-a wrench of the ball whose contacts the lanes are going through, carried
// from lane to lane and batch to batch. Each lane adds its wrench to it (starting
// again from zero at a new ball: 0 + F, as the scalar pass starts from zero) and
// stores the sum in the ball's a_side slot, which the ball's last lane leaves at its
// total. Stored, never reloaded: adding into a_side in memory made each lane wait
// for the store of the lane before (the hottest samples of a first version).
struct RunningWrench {
  std::int32_t ball = -1;
  double sum[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
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
  // law_linear.hpp's LinearLaw::force (spring_dashpot_contact), lane by lane.
  const vd fn = kn * overlap;
  L3 f = fn * normal;
  const vd zero = splat(0.0);
  L3 s{zero, zero, zero};
  vd slip = zero;
  int sliding_lanes = 0;
  if constexpr (kFriction) {
    const vd vn = dot(vrel, normal);
    s = load3(v.shear_force, cc);
    const vd old_mag2 = dot(s, s);
    const vd off_plane = dot(s, normal);
    s = s - off_plane * normal;
    const vm turned = (off_plane * off_plane > splat(0x1p-54) * old_mag2) & touch;
    if (any(turned)) {
      const vd new_mag2 = dot(s, s);
      s = select(turned & (new_mag2 > zero), vsqrt(old_mag2 / new_mag2) * s, s);
    }
    const L3 vs = vrel - vn * normal;
    s = s - (ks * splat(v.dt)) * vs;
    const vd limit = mu * fn;
    const vd mag2 = dot(s, s);
    const vm sliding = (mag2 > limit * limit) & touch;
    sliding_lanes = lane_bits(sliding);
    if (sliding_lanes != 0) {
      const vd mag = vsqrt(mag2);
      slip = select(sliding & (ks > zero), limit * (mag - limit) / ks, zero);
      s = select(sliding, (limit / mag) * s, s);
    }
    f = f + s;
  }
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
  alignas(64) double out[kRows][kLanes];
  const auto put = [&](int row, vd x) { *reinterpret_cast<vd*>(out[row]) = x; };
  put(kFx, fa.x), put(kFy, fa.y), put(kFz, fa.z);
  put(kTax, ta.x), put(kTay, ta.y), put(kTaz, ta.z);
  put(kBfx, fb.x), put(kBfy, fb.y), put(kBfz, fb.z);
  put(kTbx, tb.x), put(kTby, tb.y), put(kTbz, tb.z);
  put(kSx, s.x), put(kSy, s.y), put(kSz, s.z);
  put(kFn, select(touch, fn, zero));
  put(kSlip, slip);
  const int touching = lane_bits(touch);
  for (int k = 0; k < n; ++k) {
    const long c = cc[k];
    v.active[c] = std::uint8_t((touching >> k) & 1);
    v.normal_force[c] = out[kFn][k];
    if constexpr (kFriction) {
      double* const sf = v.shear_force + 3 * c;
      sf[0] = out[kSx][k], sf[1] = out[kSy][k], sf[2] = out[kSz][k];
    }
    double* const bw = v.b_wrench + 6 * c;
    for (int q = 0; q < 6; ++q) bw[q] = out[kBfx + q][k];
    const std::int32_t i = ia[k];
    const std::uint64_t keep = -std::uint64_t(i == run.ball);  // all ones: same ball
    double* const aw = v.a_side + 6 * long(i);
    for (int q = 0; q < 6; ++q) {
      const double carried = std::bit_cast<double>(std::bit_cast<std::uint64_t>(run.sum[q]) & keep);
      run.sum[q] = carried + out[kFx + q][k];
      aw[q] = run.sum[q];
    }
    run.ball = i;
  }
  // Slip work, only where a lane slid (rare once a bed settles): touching slip_total
  // for every contact would pull its cache lines in every step.
  if constexpr (kFriction) {
    if (sliding_lanes != 0 && v.slip_total != nullptr)
      for (int k = 0; k < n; ++k)
        if ((sliding_lanes >> k) & 1) v.slip_total[cc[k]] += out[kSlip][k];
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
