// The PFC3D linear contact law (Lu & McDowell 2007, section "Contact model"): a normal
// spring kn·overlap, an incremental shear spring ks capped by Coulomb at mu·Fn, and
// optional dashpots. The two entities' springs act in series. The SIMD sphere kernel
// (sphere_kernel_lanes.hpp) evaluates this law lane by lane and gives its bits.
#pragma once

#include <limits>

#include "engine/contact_law.hpp"

namespace ballast {

struct LinearLaw {
  static constexpr std::string_view kName = "linear";
  static constexpr std::string_view kDescription =
      "PFC3D linear: kn·overlap, incremental ks capped at mu·Fn, optional dashpots";
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static constexpr LawParameter kParameters[] = {
      {"kn", &Material::kn, 0.0, kInf, true, "> 0 N/m"},
      {"ks", &Material::ks, 0.0, kInf, false, ">= 0 N/m"},
  };
  static constexpr bool kUsesRadius = false;
  static constexpr bool kSphereKernel = true;

  static PairProperties mix(const Material& a, const Material& b) {
    return {series_stiffness(a.kn, b.kn), series_stiffness(a.ks, b.ks),
            contact_friction(a.mu, b.mu)};
  }

  template <bool kFriction, bool kDamped>
  [[gnu::always_inline]] static ContactResult force(const ContactState& c, const PairProperties& p,
                                                    V3& shear_force) {
    double cn = 0.0, cs = 0.0;
    if constexpr (kDamped) {
      cn = dashpot_coefficient(c.damping_ratio, c.m_eff, p.normal);
      cs = dashpot_coefficient(c.damping_ratio, c.m_eff, p.shear);
    }
    return spring_dashpot_contact<kFriction, kDamped>(c, p.normal * c.overlap, p.shear, p.mu, cn,
                                                      cs, shear_force);
  }

  static ContactStiffness stiffness(const PairProperties& p, double /*radius*/,
                                    double /*overlap*/) {
    return {p.normal, p.shear};
  }

  // The overlap that gives an elastic normal force fn, m.
  static double overlap_at(const PairProperties& p, double /*radius*/, double fn) {
    return p.normal > 0.0 ? fn / p.normal : 0.0;
  }

  // A contact with an identical ball: the two springs in series halve the stiffness.
  static ContactStiffness floor_stiffness(const Material& m, double /*radius*/, double /*mass*/,
                                          double /*max_speed*/) {
    return {0.5 * m.kn, 0.5 * m.ks};
  }

  // Fn²/(2kn) + |Fs|²/(2ks), J.
  static double elastic_energy(const PairProperties& p, double /*radius*/, double fn,
                               double shear2) {
    double e = p.normal > 0.0 ? 0.5 * fn * fn / p.normal : 0.0;
    if (p.shear > 0.0) e += 0.5 * shear2 / p.shear;
    return e;
  }
};

}  // namespace ballast
