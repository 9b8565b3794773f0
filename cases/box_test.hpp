// Geometry and material numbers of the paper's box test (Lu & McDowell 2007, §3;
// McDowell et al. box: 700 × 300 × 450 mm, rubber base). SI units.
#pragma once

#include "engine/material.hpp"
#include "engine/types.hpp"

namespace ballast::box_test {

inline constexpr double kLength = 0.700;  // m, x
inline constexpr double kWidth = 0.300;   // m, y
inline constexpr double kHeight = 0.450;  // m, z

inline constexpr double kBallStiffness = 5.08e9;    // N/m, kn = ks for balls, sleeper, walls
inline constexpr double kRubberStiffness = 2.54e6;  // N/m, kn = ks for the rubber base
inline constexpr double kDensity = 2600.0;          // kg/m³
inline constexpr double kFrictionCompaction = 0.3;
inline constexpr double kFrictionLoading = 0.5;
inline constexpr double kSphereDiameter = 0.03625;  // m, the 1,936 spheres of Fig. 9a
inline constexpr int kSphereCount = 1936;

// Hertz–Mindlin moduli for a scene that chooses that law (the paper uses the linear
// law only, so these are ours; docs/BOX_TEST.md, "Contact law"): granite ballast,
// steel walls and sleeper, and a base whose E makes a 36.25 mm ball under 400 N
// sink as far (0.16 mm) as on the paper's 2.54e6 N/m rubber spring.
inline constexpr double kBallastYoungModulus = 50e9, kBallastPoissonRatio = 0.25;  // Pa, -
inline constexpr double kSteelYoungModulus = 200e9, kSteelPoissonRatio = 0.3;      // Pa, -
inline constexpr double kBaseYoungModulus = 0.9e9, kBasePoissonRatio = 0.45;       // Pa, -

inline Material with_friction(Material m, double mu) {
  m.mu = mu;
  return m;
}

inline Material ballast_material(double mu = kFrictionCompaction) {
  return {kBallStiffness, kBallStiffness, mu, kBallastYoungModulus, kBallastPoissonRatio};
}
inline Material wall_material(double mu = kFrictionCompaction) {
  return {kBallStiffness, kBallStiffness, mu, kSteelYoungModulus, kSteelPoissonRatio};
}
inline Material rubber_base(double mu = kFrictionCompaction) {
  return {kRubberStiffness, kRubberStiffness, mu, kBaseYoungModulus, kBasePoissonRatio};
}

}  // namespace ballast::box_test
