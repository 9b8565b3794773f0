// Contact laws as small stateless functions (LAMMPS GRANULAR style): inputs in,
// force out, the only state passed by reference is the contact's shear history.
// The force loop in forces.cpp is the one place that iterates contacts; a law only
// evaluates one contact.
#pragma once

#include <cmath>
#include <string_view>

#include "engine/types.hpp"

namespace ballast {

// Everything a law needs about one contact at time t.
struct ContactState {
  double overlap;  // m, > 0
  Vec3 normal;     // unit, from b towards a
  Vec3 vrel;       // m/s, velocity of a minus velocity of b at the contact point (t - dt/2)
  double kn, ks;   // N/m, already combined in series
  double mu;       // friction coefficient
  double cn, cs;   // N·s/m, normal and shear dashpot coefficients (0 when undamped)
  double dt;       // s
};

struct ContactResult {
  Vec3 force;           // N, on a
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
template <bool kFriction>
inline ContactResult linear_contact(const ContactState& c, Vec3& shear_force) {
  ContactResult r{};
  r.normal_force = c.kn * c.overlap;
  const double vn = c.vrel.dot(c.normal);
  Vec3 f = r.normal_force * c.normal;
  bool sliding = false;
  if constexpr (kFriction) {
    const double old_mag2 = shear_force.squaredNorm();
    if (old_mag2 > 0.0) {
      shear_force -= shear_force.dot(c.normal) * c.normal;
      const double new_mag2 = shear_force.squaredNorm();
      if (new_mag2 > 0.0) shear_force *= std::sqrt(old_mag2 / new_mag2);
    }
    const Vec3 vs = c.vrel - vn * c.normal;
    shear_force -= (c.ks * c.dt) * vs;
    const double limit = c.mu * r.normal_force;
    const double mag2 = shear_force.squaredNorm();
    if (mag2 > limit * limit) {
      const double mag = std::sqrt(mag2);
      // The spring would have stretched (mag - limit)/ks beyond the slider; that
      // displacement slips against a friction force of `limit`.
      r.slip_work = c.ks > 0.0 ? limit * (mag - limit) / c.ks : 0.0;
      shear_force *= limit / mag;
      sliding = true;
    }
    f += shear_force;
    if (c.cs > 0.0 && !sliding) {
      const Vec3 fd = -c.cs * vs;
      f += fd;
      r.viscous_work -= fd.dot(vs) * c.dt;
    }
  }
  if (c.cn > 0.0) {
    const double fdn = -c.cn * vn;
    f += fdn * c.normal;
    r.viscous_work -= fdn * vn * c.dt;
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
