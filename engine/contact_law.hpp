// Contact laws as small stateless functions (LAMMPS GRANULAR style): inputs in,
// force out, the only state passed by reference is the contact's shear history.
// The force loop in forces.cpp is the one place that iterates contacts; a law only
// evaluates one contact.
#pragma once

#include <cmath>
#include <string_view>

#include "engine/types.hpp"
#include "engine/v3.hpp"

namespace ballast {

// Everything a law needs about one contact at time t.
struct ContactState {
  double overlap;  // m, > 0
  V3 normal;       // unit, from b towards a
  V3 vrel;         // m/s, velocity of a minus velocity of b at the contact point (t - dt/2)
  double kn, ks;   // N/m, already combined in series
  double mu;       // friction coefficient
  double cn, cs;   // N·s/m, normal and shear dashpot coefficients (0 when undamped)
  double dt;       // s
};

struct ContactResult {
  V3 force;             // N, on a
  double normal_force;  // N, kn·overlap
  double slip_work;     // J dissipated by Coulomb slip this step
  double viscous_work;  // J dissipated by the dashpots this step
};

// PFC3D linear model: normal spring kn·overlap, incremental shear spring ks capped
// by Coulomb at mu·Fn, optional dashpots in parallel with both springs.
//
// The stored shear force is first rotated into the current contact plane (projected,
// then rescaled to keep its magnitude), so a contact that rolls keeps its shear load
// instead of leaking it through the normal. The increment uses the relative shear
// velocity: ΔFs = −ks·vs·dt.
//
// Dashpot force is not clamped: the normal force may briefly turn attractive at the
// end of a damped impact, which is what gives the closed-form restitution
// e = exp(−πβ/√(1−β²)). As in PFC, the shear dashpot is off while the contact slides.
//
// Always inlined into the force loop, where the state and result then live in
// registers (GCC otherwise kept it out of line and passed them through memory).
template <bool kFriction, bool kDamped>
[[gnu::always_inline]] inline ContactResult linear_contact(const ContactState& c, V3& shear_force) {
  ContactResult r{};
  r.normal_force = c.kn * c.overlap;
  const double vn = dot(c.vrel, c.normal);
  V3 f = r.normal_force * c.normal;
  if constexpr (kFriction) {
    bool sliding = false;
    const double old_mag2 = dot(shear_force, shear_force);
    const double off_plane = dot(shear_force, c.normal);
    shear_force = shear_force - off_plane * c.normal;
    // The rescale factor is 1/√(1 − q), q = off_plane²/old_mag2: the normal turns by
    // √q radians in a step. Below q = 2⁻⁵⁴ the factor is 1 + q/2 < 1 + 2⁻⁵⁵, which
    // rounds to exactly 1, so the square root and division are skipped. In a settled
    // bed that is nearly every contact (the normal turns ~1e-9 rad per µs step): the
    // skip saves 3.3 % of the instructions of a sphere ball-step; the time it saves
    // is below this host's noise (docs/PERFORMANCE.md, "What bought what").
    if (off_plane * off_plane > 0x1p-54 * old_mag2) {
      const double new_mag2 = dot(shear_force, shear_force);
      if (new_mag2 > 0.0) shear_force = std::sqrt(old_mag2 / new_mag2) * shear_force;
    }
    const V3 vs = c.vrel - vn * c.normal;
    shear_force = shear_force - (c.ks * c.dt) * vs;
    const double limit = c.mu * r.normal_force;
    const double mag2 = dot(shear_force, shear_force);
    if (mag2 > limit * limit) {
      const double mag = std::sqrt(mag2);
      // The spring would have stretched (mag - limit)/ks beyond the slider; that
      // displacement slips against a friction force of `limit`.
      r.slip_work = c.ks > 0.0 ? limit * (mag - limit) / c.ks : 0.0;
      shear_force = (limit / mag) * shear_force;
      sliding = true;
    }
    f += shear_force;
    if constexpr (kDamped) {
      if (c.cs > 0.0 && !sliding) {
        const V3 fd = (-c.cs) * vs;
        f += fd;
        r.viscous_work -= dot(fd, vs) * c.dt;
      }
    }
  }
  if constexpr (kDamped) {
    if (c.cn > 0.0) {
      const double fdn = -c.cn * vn;
      f += fdn * c.normal;
      r.viscous_work -= fdn * vn * c.dt;
    }
  }
  r.force = f;
  return r;
}

// Dashpot coefficient for a damping ratio β on a spring k between effective mass m:
// c = 2β·√(m·k).
inline double dashpot_coefficient(double ratio, double m_eff, double k) {
  return ratio > 0.0 ? 2.0 * ratio * std::sqrt(m_eff * k) : 0.0;
}

// The registry of contact models. Adding one means writing its function above, a
// row here and its branch in forces.cpp; scenes name models by `name`
// (SimulationSettings::contact_model), and an unknown name is refused at set-up
// with this table's names.
struct ContactModelInfo {
  std::string_view name;
  std::string_view description;
};
inline constexpr ContactModelInfo kContactModels[] = {
    {"linear", "PFC3D linear: kn·overlap, incremental ks capped at mu·Fn, optional dashpots"},
};

}  // namespace ballast
