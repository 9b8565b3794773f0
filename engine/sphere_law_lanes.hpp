// law_linear.hpp's LinearLaw::force (contact_law.hpp's spring_dashpot_contact, no
// dashpots) lane by lane, for the sphere kernels' ball–ball and ball–plane contacts.
// Included after sphere_lane_ops.hpp by one file per instruction set; every lane
// performs the scalar law's IEEE operations in the scalar order, and the law's two
// branches (the shear force turned into the new contact plane, the Coulomb cap)
// become selects computed only when a lane needs them (sphere_kernel.hpp).
#pragma once

namespace ballast {
namespace {

// What the law hands back per lane: the total force on side a (N), the new shear
// force (N), the slip work (J, zero where the lane did not slide) and which lanes slid.
struct LawLanes {
  L3 force;
  L3 shear;
  vd slip;
  int sliding_lanes;
};

// The contact's normal (unit, from b towards a), the relative velocity of a's contact
// point against b's (m/s), the elastic normal force kn·overlap (N), the pair's ks (N/m)
// and mu, the step (s), the lanes whose entities touch, and the shear force carried
// from the last step (N; zeros without friction).
template <bool kFriction>
[[gnu::always_inline]] inline LawLanes linear_law(const L3& normal, const L3& vrel, vd fn, vd ks,
                                                  vd mu, double dt, vm touch, L3 s) {
  const vd zero = splat(0.0);
  L3 f = fn * normal;
  vd slip = zero;
  int sliding_lanes = 0;
  if constexpr (kFriction) {
    const vd vn = dot(vrel, normal);
    const vd old_mag2 = dot(s, s);
    const vd off_plane = dot(s, normal);
    s = s - off_plane * normal;
    const vm turned = (off_plane * off_plane > splat(0x1p-54) * old_mag2) & touch;
    if (any(turned)) {
      const vd new_mag2 = dot(s, s);
      s = select(turned & (new_mag2 > zero), vsqrt(old_mag2 / new_mag2) * s, s);
    }
    const L3 vs = vrel - vn * normal;
    s = s - (ks * splat(dt)) * vs;
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
  return {f, s, slip, sliding_lanes};
}

}  // namespace
}  // namespace ballast
