// Hertz–Mindlin: the Hertz normal force of two elastic spheres and Mindlin's no-slip
// tangential spring, capped by Coulomb: EDEM's default law, and LAMMPS GRANULAR's
// "hertz/material" normal with "tangential mindlin".
//
//   E* = 1/((1 − ν₁²)/E₁ + (1 − ν₂²)/E₂),  G* = 1/((2 − ν₁)/G₁ + (2 − ν₂)/G₂),  G = E/(2(1 + ν))
//   a = √(R*·δ)                  contact radius, m
//   Fn = (4/3)·E*·a·δ            normal force (Hertz), N
//   kn = 2·E*·a = dFn/dδ         normal tangent stiffness, N/m
//   kt = 8·G*·a                  tangential stiffness (Mindlin, no slip), N/m
//
// A wall is a flat elastic body: R* is the ball's radius. The dashpots follow the
// tangent stiffness, c = 2β·√(m*·k), so they grow as δ^¼, the form (Tsuji et al.
// 1992) whose restitution does not depend on the impact speed.
#pragma once

#include <cmath>
#include <limits>

#include "engine/contact_law.hpp"

namespace ballast {

struct HertzMindlinLaw {
  static constexpr std::string_view kName = "hertz_mindlin";
  static constexpr std::string_view kDescription =
      "Hertz normal (4/3)E*·√R*·δ^1.5, Mindlin no-slip shear 8G*·√(R*δ) capped at mu·Fn";
  static constexpr LawParameter kParameters[] = {
      {"young_modulus", &Material::young_modulus, 0.0, std::numeric_limits<double>::infinity(),
       true, "> 0 Pa"},
      {"poisson_ratio", &Material::poisson_ratio, 0.0, 0.5, false, "in [0, 0.5)"},
  };
  static constexpr bool kUsesRadius = true;
  static constexpr bool kSphereKernel = false;

  // (4/3)·E* and 8·G* of the pair.
  static PairProperties mix(const Material& a, const Material& b) {
    const auto shear_modulus = [](const Material& m) {
      return m.young_modulus / (2.0 * (1.0 + m.poisson_ratio));
    };
    const double e_star = 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.young_modulus +
                                 (1.0 - b.poisson_ratio * b.poisson_ratio) / b.young_modulus);
    const double g_star = 1.0 / ((2.0 - a.poisson_ratio) / shear_modulus(a) +
                                 (2.0 - b.poisson_ratio) / shear_modulus(b));
    return {4.0 / 3.0 * e_star, 8.0 * g_star, contact_friction(a.mu, b.mu)};
  }

  template <bool kFriction, bool kDamped>
  [[gnu::always_inline]] static ContactResult force(const ContactState& c, const PairProperties& p,
                                                    V3& shear_force) {
    const double a = std::sqrt(c.radius * c.overlap);
    const double kt = p.shear * a;
    double cn = 0.0, cs = 0.0;
    if constexpr (kDamped) {
      cn = dashpot_coefficient(c.damping_ratio, c.m_eff, 1.5 * p.normal * a);
      cs = dashpot_coefficient(c.damping_ratio, c.m_eff, kt);
    }
    return spring_dashpot_contact<kFriction, kDamped>(c, p.normal * a * c.overlap, kt, p.mu, cn, cs,
                                                      shear_force);
  }

  static ContactStiffness stiffness(const PairProperties& p, double radius, double overlap) {
    const double a = std::sqrt(radius * overlap);
    return {1.5 * p.normal * a, p.shear * a};
  }

  // The overlap that gives an elastic normal force fn: δ = (Fn/((4/3)E*·√R*))^(2/3), m.
  static double overlap_at(const PairProperties& p, double radius, double fn) {
    if (fn <= 0.0 || p.normal <= 0.0) return 0.0;
    return std::cbrt(fn * fn / (p.normal * p.normal * radius));
  }

  // The stiffest contact a body with none must be ready for: a head-on impact with
  // an identical ball at the largest speed a body may have (SimulationSettings::
  // max_speed), at its deepest overlap δ = (15·m*·v²/(16·E*·√R*))^(2/5).
  static ContactStiffness floor_stiffness(const Material& m, double radius, double mass,
                                          double max_speed) {
    const PairProperties p = mix(m, m);
    const double r_eff = 0.5 * radius, m_eff = 0.5 * mass, e_star = 0.75 * p.normal;
    const double depth =
        std::pow(15.0 * m_eff * max_speed * max_speed / (16.0 * e_star * std::sqrt(r_eff)), 0.4);
    return stiffness(p, r_eff, depth);
  }

  // Normal: ∫Fn dδ = (2/5)·Fn·δ; shear: |Fs|²/(2kt), J.
  static double elastic_energy(const PairProperties& p, double radius, double fn, double shear2) {
    const double overlap = overlap_at(p, radius, fn);
    if (overlap <= 0.0) return 0.0;
    double e = 0.4 * fn * overlap;
    const double kt = p.shear * std::sqrt(radius * overlap);
    if (kt > 0.0) e += 0.5 * shear2 / kt;
    return e;
  }
};

}  // namespace ballast
