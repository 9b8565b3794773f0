// Contact properties of balls and walls, and how two of them combine at a contact.
#pragma once

namespace ballast {

// What an entity (ball material or wall) brings to a contact. Each contact law reads
// the members its LawParameter table names (contact_law.hpp) and ignores the others,
// so one Material serves every law a scene may choose.
struct Material {
  double kn = 0.0;             // linear law: normal stiffness of the entity, N/m
  double ks = 0.0;             // linear law: shear stiffness of the entity, N/m
  double mu = 0.0;             // Coulomb friction coefficient, every law
  double young_modulus = 0.0;  // Hertz–Mindlin: E, Pa
  double poisson_ratio = 0.0;  // Hertz–Mindlin: ν
};

// PFC's linear contact model puts the two entities' springs in series:
// k = k1·k2/(k1 + k2). Two balls of 5.08e9 N/m give 2.54e9 N/m; a ball on the
// paper's 2.54e6 N/m rubber base gives about 2.5387e6 N/m.
inline double series_stiffness(double k1, double k2) {
  const double sum = k1 + k2;
  return sum > 0.0 ? k1 * k2 / sum : 0.0;
}

// PFC takes the smaller of the two friction coefficients.
inline double contact_friction(double mu1, double mu2) {
  return mu1 < mu2 ? mu1 : mu2;
}

}  // namespace ballast
