// The sphere kernel's leapfrog (sphere_kernel.hpp), lane-generic: one lane per
// sphere, kLanes consecutive spheres a pass. Included by one file per instruction
// set (sphere_lane_ops.hpp lists what that file defines).
//
// Lane by lane, the operations of integrator.cpp's update_body for a sphere, in its
// order: PFC local damping, v += (dt/m)·F, x += dt·v, ω += (dt/I)·M, the rotation
// Σ ω·dt, the energy ledger with mid-step velocities, the ball's new place, its move
// since the neighbour build and the blow-up check. The running maximum keeps
// std::max's rule (a < b ? b : a), so a NaN never enters it, as in the scalar loop.
#pragma once

#include <cstdint>

#include "engine/sphere_kernel.hpp"
#include "engine/sphere_lane_ops.hpp"

namespace ballast {
namespace {

// PFC local damping on each component: f − α·|f|·sign(v) (body_step's local_damp).
[[gnu::always_inline]] inline vd local_damp(vd f, vd v, vd alpha) {
  const vd cut = alpha * vabs(f);
  const vd zero = splat(0.0);
  return select(v > zero, f - cut, select(v < zero, f + cut, f));
}
[[gnu::always_inline]] inline L3 local_damp(const L3& f, const L3& v, vd alpha) {
  return {local_damp(f.x, v.x, alpha), local_damp(f.y, v.y, alpha), local_damp(f.z, v.z, alpha)};
}

template <bool kDamped, bool kLedger>
[[gnu::always_inline]] inline void update_lanes(const SphereUpdateView& u, std::int32_t b0,
                                                vd& shift2, SphereUpdateReport& report) {
  const long o = 3L * b0;
  const vd dt = splat(u.dt), alpha = splat(u.local_damping);
  const L3 f_raw = load_aos3(u.force + o), m_raw = load_aos3(u.torque + o);
  const L3 v_old = load_aos3(u.velocity + o), w_old = load_aos3(u.angular_velocity + o);
  const L3 f = kDamped ? local_damp(f_raw, v_old, alpha) : f_raw;
  const L3 torque = kDamped ? local_damp(m_raw, w_old, alpha) : m_raw;

  const L3 v_new = v_old + (dt * loadu(u.inv_mass + b0)) * f;
  const L3 x_new = load_aos3(u.position + o) + dt * v_new;
  store_aos3(u.velocity + o, v_new);
  store_aos3(u.position + o, x_new);
  const L3 w_new = w_old + (dt * load_aos3(u.inv_inertia + o).x) * torque;
  store_aos3(u.angular_velocity + o, w_new);
  store_aos3(u.rotation + o, load_aos3(u.rotation + o) + dt * w_new);

  if constexpr (kLedger) {
    const vd half = splat(0.5);
    const L3 v_mid = half * (v_old + v_new);
    const L3 g{splat(u.gravity[0]), splat(u.gravity[1]), splat(u.gravity[2])};
    storeu(u.gravity_work + b0,
           loadu(u.gravity_work + b0) + (dt * loadu(u.mass + b0)) * dot(g, v_mid));
    if constexpr (kDamped) {
      const L3 w_mid = half * (w_old + w_new);
      storeu(u.damping_dissipated + b0,
             loadu(u.damping_dissipated + b0) -
                 dt * (dot(f - f_raw, v_mid) + dot(torque - m_raw, w_mid)));
    }
  }

  store_aos3(u.ball_position + o, x_new);
  const L3 moved = x_new - load_aos3(u.reference + o);
  const vd d2 = dot(moved, moved);
  shift2 = select(shift2 < d2, d2, shift2);

  const vd speed2 = dot(v_new, v_new);
  const vm bad =
      ~finite(speed2) | ~finite(dot(w_new, w_new)) | (speed2 > splat(u.max_speed * u.max_speed));
  const int bits = lane_bits(bad);
  if (bits != 0 && b0 + __builtin_ctz(bits) < report.bad) report.bad = b0 + __builtin_ctz(bits);
}

template <bool kDamped, bool kLedger>
std::int32_t update_spheres(const SphereUpdateView& view, std::int32_t lo, std::int32_t hi,
                            SphereUpdateReport& report) {
  const SphereUpdateView u = view;  // a local copy: the stores may alias the view
  vd shift2 = splat(report.shift2);
  std::int32_t b = lo;
  for (; b + kLanes <= hi; b += kLanes) update_lanes<kDamped, kLedger>(u, b, shift2, report);
  alignas(64) double lane_shift2[kLanes];
  storeu(lane_shift2, shift2);
  for (int k = 0; k < kLanes; ++k)
    if (report.shift2 < lane_shift2[k]) report.shift2 = lane_shift2[k];
  return b;
}

// The update for this instruction set: local damping and the ledger are template
// arguments, so that a scene without them carries no test for them.
std::int32_t update_contiguous_spheres(const SphereUpdateView& u, std::int32_t lo, std::int32_t hi,
                                       SphereUpdateReport& report) {
  if (u.local_damping > 0.0)
    return u.ledger ? update_spheres<true, true>(u, lo, hi, report)
                    : update_spheres<true, false>(u, lo, hi, report);
  return u.ledger ? update_spheres<false, true>(u, lo, hi, report)
                  : update_spheres<false, false>(u, lo, hi, report);
}

}  // namespace
}  // namespace ballast
