// Small scene builders shared by the verification tests.
#pragma once

#include "engine/simulation.hpp"

namespace ballast::scenes {

// An empty simulation in a cube [-L, L]³ with no gravity and no damping: tests
// switch on exactly what they verify.
inline SimulationSettings bare_settings(double half_size = 1.0) {
  SimulationSettings s;
  s.domain_lo = Vec3::Constant(-half_size);
  s.domain_hi = Vec3::Constant(half_size);
  s.gravity = Vec3::Zero();
  s.local_damping = 0.0;
  s.damping_ratio = 0.0;
  return s;
}

inline double sphere_mass(double r, double density) {
  return density * 4.0 / 3.0 * kPi * r * r * r;
}

inline Wall plane_wall(const Vec3& point, const Vec3& normal, const Material& m) {
  Wall w;
  w.name = "plane";
  w.point = point;
  w.normal = normal.normalized();
  w.material = m;
  return w;
}

}  // namespace ballast::scenes
