// What every contact law shares (LAMMPS GRANULAR style: laws are small stateless
// units, the force loop in forces.cpp is the one place that iterates contacts).
// A law (law_linear.hpp, law_hertz_mindlin.hpp) is a struct of static members:
//
//   kName, kDescription    its name in scenes and studies, one line on what it is
//   kParameters            the Material members it reads, with their ranges
//   kUsesRadius            whether force() reads ContactState::radius
//   kSphereKernel          whether the SIMD sphere kernel evaluates it (linear only)
//   mix(a, b)              two entities' Materials -> the pair's PairProperties
//   force<F, D>(c, p, s)   one contact's force; s is its shear history (F: friction,
//                          D: dashpots)
//   stiffness(p, R, d)     normal and shear tangent stiffness at overlap d, for the
//                          critical timestep and the servo
//   overlap_at(p, R, fn)   the overlap at which the elastic normal force is fn
//   floor_stiffness(...)   the stiffness a body with no contact must be ready for
//   elastic_energy(p, R, fn, fs2)  the energy stored in a contact's springs
//
// contact_laws.hpp lists the laws in one table and dispatches to them.
#pragma once

#include <cmath>
#include <string_view>

#include "engine/material.hpp"
#include "engine/types.hpp"
#include "engine/v3.hpp"

namespace ballast {

// The pair constants a law mixes once per pair of entities (pair_table.hpp) and reads
// at every contact. Their meaning is the law's; the SIMD sphere kernel reads the
// linear law's as three packed doubles.
struct PairProperties {
  double normal = 0.0;  // linear: kn in series, N/m; Hertz–Mindlin: (4/3)·E*, Pa
  double shear = 0.0;   // linear: ks in series, N/m; Hertz–Mindlin: 8·G*, Pa
  double mu = 0.0;      // the smaller friction coefficient
};

// Everything a law needs about one contact at time t, besides its pair constants.
struct ContactState {
  double overlap;        // m, > 0
  V3 normal;             // unit, from b towards a
  V3 vrel;               // m/s, velocity of a minus velocity of b at the contact point (t - dt/2)
  double radius;         // m, effective radius R* = ra·rb/(ra + rb) (a wall: the ball's); read
                         // only by laws with kUsesRadius
  double m_eff;          // kg, effective mass, read only with dashpots
  double damping_ratio;  // dashpot damping ratio β, read only with dashpots
  double dt;             // s
};

struct ContactResult {
  V3 force;             // N, on a
  double normal_force;  // N, the elastic normal force
  double slip_work;     // J dissipated by Coulomb slip this step
  double viscous_work;  // J dissipated by the dashpots this step
};

// Normal and shear stiffness of a contact, N/m.
struct ContactStiffness {
  double kn = 0.0, ks = 0.0;
};

// One Material member a law reads, and the values it allows.
struct LawParameter {
  std::string_view name;  // as scenes write it: "kn", "young_modulus"
  double Material::*member;
  double lo, hi;  // allowed: lo < x (lo_open) or lo <= x, and x < hi
  bool lo_open;
  std::string_view allowed;  // the range as errors print it: "> 0 N/m"
  bool allows(double x) const { return std::isfinite(x) && (lo_open ? x > lo : x >= lo) && x < hi; }
};

// Dashpot coefficient for a damping ratio β on a spring k between effective mass m:
// c = 2β·√(m·k).
inline double dashpot_coefficient(double ratio, double m_eff, double k) {
  return ratio > 0.0 ? 2.0 * ratio * std::sqrt(m_eff * k) : 0.0;
}

// A normal force fn, an incremental shear spring ks capped by Coulomb at mu·fn, and
// optional dashpots cn, cs in parallel with both springs: the part every law here
// shares once it has its normal force and stiffnesses.
//
// The stored shear force is first rotated into the current contact plane (projected,
// then rescaled to keep its magnitude), so a contact that rolls keeps its shear load
// instead of leaking it through the normal. The increment uses the relative shear
// velocity: ΔFs = −ks·vs·dt.
//
// Dashpot force is not clamped: the normal force may briefly turn attractive at the
// end of a damped impact, which is what gives the linear law's closed-form
// restitution e = exp(−πβ/√(1−β²)). As in PFC, the shear dashpot is off while the
// contact slides.
//
// Always inlined into the force loop, where the state and result then live in
// registers (GCC otherwise kept it out of line and passed them through memory).
template <bool kFriction, bool kDamped>
[[gnu::always_inline]] inline ContactResult spring_dashpot_contact(const ContactState& c, double fn,
                                                                   double ks, double mu, double cn,
                                                                   double cs, V3& shear_force) {
  ContactResult r{};
  r.normal_force = fn;
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
    // bed that is nearly every contact (the normal turns ~1e-9 rad per µs step).
    if (off_plane * off_plane > 0x1p-54 * old_mag2) {
      const double new_mag2 = dot(shear_force, shear_force);
      if (new_mag2 > 0.0) shear_force = std::sqrt(old_mag2 / new_mag2) * shear_force;
    }
    const V3 vs = c.vrel - vn * c.normal;
    shear_force = shear_force - (ks * c.dt) * vs;
    const double limit = mu * r.normal_force;
    const double mag2 = dot(shear_force, shear_force);
    if (mag2 > limit * limit) {
      const double mag = std::sqrt(mag2);
      // The spring would have stretched (mag - limit)/ks beyond the slider; that
      // displacement slips against a friction force of `limit`.
      r.slip_work = ks > 0.0 ? limit * (mag - limit) / ks : 0.0;
      shear_force = (limit / mag) * shear_force;
      sliding = true;
    }
    f += shear_force;
    if constexpr (kDamped) {
      if (cs > 0.0 && !sliding) {
        const V3 fd = (-cs) * vs;
        f += fd;
        r.viscous_work -= dot(fd, vs) * c.dt;
      }
    }
  }
  if constexpr (kDamped) {
    if (cn > 0.0) {
      const double fdn = -cn * vn;
      f += fdn * c.normal;
      r.viscous_work -= fdn * vn * c.dt;
    }
  }
  r.force = f;
  return r;
}

}  // namespace ballast
