// The two rotation integrators for many-ball bodies, selectable per scene.
//
//   pfc   Lu & McDowell 2007 eq 17 as PFC3D 3.x computes it: the moment is taken
//         into the principal frame, ω_i += dt·M_i/I_i, the gyroscopic term [W] (the
//         ω×Iω coupling) is dropped. Cheap, and right while ω stays on a principal
//         axis or is small; a torque-free body spinning off-axis keeps a constant
//         world ω, so its |L| and energy drift (measured in docs/TRADEOFFS.md).
//   full  Euler's equations with the gyroscopic term. The state is the angular
//         momentum L in the world frame at half steps, so the kick L += dt·M is
//         exact: a torque-free body keeps L to the last bit. The drift (free
//         rotation over dt with L fixed) is split into exact rotations about the
//         principal axes in the symmetric order 1,2,3,2,1 (Dullweber, Leimkuhler &
//         McLachlan 1997): each sub-rotation conserves |L| exactly, the splitting is
//         symplectic and time-reversible, so the energy error stays bounded at
//         O((ω·dt)²) instead of drifting.
//
// One-ball bodies never come here: a sphere's inertia is isotropic, ω += dt·M/I.
#pragma once

#include <string_view>

#include "engine/types.hpp"

namespace ballast {

enum class RotationIntegrator { kPfc, kFull };

// "pfc", "full".
const char* rotation_integrator_name(RotationIntegrator r);
// Inverse of rotation_integrator_name; throws SetupError naming the value and the
// allowed names.
RotationIntegrator parse_rotation_integrator(std::string_view name);

// State of one clump across a rotation step: orientation q (principal frame →
// world), ω in the world frame and, for `full`, L in the world frame.
struct RotationState {
  Quat orientation;
  Vec3 angular_velocity;  // rad/s, world frame, half step
  Vec3 angular_momentum;  // kg·m²/s, world frame, half step (full only)
};

// pfc: eq 17 with [W] = 0, then the orientation turns by ω·dt.
void rotate_pfc(RotationState& s, const Vec3& torque, const Vec3& inv_inertia, double dt);

// full: L += dt·M, then free rotation over dt by the 1,2,3,2,1 splitting; ω from
// the new orientation. inv_inertia: inverse principal moments, 1/(kg·m²).
void rotate_full(RotationState& s, const Vec3& torque, const Vec3& inv_inertia, double dt);

// sin x and cos x for the `full` integrator's sub-rotations: the Taylor series to
// x⁷ and x⁶ for |x| < 2⁻⁵, where the terms left out are under half an ulp, libm
// beyond. A clump turns by micro-radians per step, and the series costs a dozen
// operations instead of a library call.
void small_angle_sin_cos(double x, double& s, double& c);

// World-frame angular momentum R·I·Rᵀ·ω of a body with principal moments `inertia`.
inline Vec3 spin_angular_momentum(const Quat& q, const Vec3& inertia, const Vec3& w) {
  return q * inertia.cwiseProduct(q.conjugate() * w);
}

}  // namespace ballast
