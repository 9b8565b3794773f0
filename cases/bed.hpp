// A bed of particles in the paper's 700 × 300 mm box: the scene behind the settling
// demo, the energy-budget and determinism tests, the dense-bed benchmarks and the
// rotation/mass-mode trade-off study. Particles start as a loose random cloud above
// the rubber base and fall.
//
// Spheres by default. With `clumps` set, each particle is a clump of that sample
// generated inside its virtual sphere (radius virtual_sphere_factor × d/2), turned
// to a random orientation, and the cloud is packed by virtual spheres so that no
// two clumps overlap at the start.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "cases/box_test.hpp"
#include "engine/clump_generator.hpp"
#include "engine/clump_mass.hpp"
#include "engine/simulation.hpp"

namespace ballast {

struct BedOptions {
  int count = box_test::kSphereCount;
  double diameter = box_test::kSphereDiameter;  // m; spheres, or clumps' nominal diameter
  double length = box_test::kLength;            // m, box x extent
  double width = box_test::kWidth;              // m, box y extent
  std::uint64_t seed = 1;
  double volume_fraction = 0.3;  // of the loose random cloud the particles start as
  bool spatial_order = true;     // false: bodies numbered at random (to measure locality)
  // Then renumbered by the engine (Simulation::sort_bodies_spatially, always): a bed
  // numbered at random and sorted, as a packing file from another code would be.
  bool engine_sort = false;
  double friction = box_test::kFrictionCompaction;
  double stiffness = box_test::kBallStiffness;  // N/m, balls and side walls (linear law)
  bool rubber_base = true;                      // false: the base is as stiff as the sides
  // The engine's settings (gravity, damping, timestep, contact law, the switches that
  // tests and benchmarks compare); make_bed sets the domain from the box.
  SimulationSettings sim;
  // Clumps instead of spheres: the sample's parameters (nominal_diameter is taken
  // from `diameter`) and how their mass is computed (sim.rotation: how they rotate).
  std::optional<ClumpParams> clumps;
  ClumpMassOptions mass;
  // Where the particles go (e.g. the centres of a settled sphere bed); empty: a loose
  // random cloud of `count` particles.
  std::vector<Vec3> centres;
};

// Top of the space the particles may occupy, m (the walls are infinite planes, so
// the initial cloud may rise above the 450 mm box and settle into it).
inline constexpr double kBedDomainTop = 2.5;

Simulation make_bed(const BedOptions& o);

// A rotation drawn uniformly from SO(3) (Shoemake 1992) from three uniform numbers
// in [0, 1).
Quat uniform_rotation(double u1, double u2, double u3);

}  // namespace ballast
