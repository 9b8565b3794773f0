// A bed of equal spheres in the paper's 700 × 300 mm box: the scene behind the
// settling demo, the energy-budget and determinism tests and the dense-bed
// benchmark. Spheres start as a loose random cloud above the rubber base and fall.
#pragma once

#include <cstdint>
#include <iosfwd>

#include "cases/box_test.hpp"
#include "engine/simulation.hpp"

namespace ballast {

struct SphereBedOptions {
  int count = box_test::kSphereCount;
  double diameter = box_test::kSphereDiameter;  // m
  double length = box_test::kLength;            // m, box x extent
  double width = box_test::kWidth;              // m, box y extent
  std::uint64_t seed = 1;
  double volume_fraction = 0.3;  // of the loose random cloud the spheres start as
  bool spatial_order = true;     // false: bodies numbered at random (to measure locality)
  double friction = box_test::kFrictionCompaction;
  double stiffness = box_test::kBallStiffness;  // N/m, balls and side walls
  bool rubber_base = true;                      // false: the base is as stiff as the sides
  double local_damping = 0.7;
  double damping_ratio = 0.0;
  double dt_safety = 0.8;  // dt = dt_safety × critical estimate
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);
  std::ostream* log = nullptr;
};

// Top of the space the spheres may occupy, m (the walls are infinite planes, so
// the initial cloud may rise above the 450 mm box and settle into it).
inline constexpr double kBedDomainTop = 2.0;

Simulation make_sphere_bed(const SphereBedOptions& o);

}  // namespace ballast
