// The scene of the side-by-side benchmark against LAMMPS and YADE (issue 7): a
// packing file in the paper's 700 × 300 × 450 mm box, open at the top, its five walls
// infinite planes, with the simplest physics all three codes share exactly:
//   every contact linear, kn = ks = 5.08e9 N/m per CONTACT (ball–ball and ball–wall),
//   Coulomb friction mu = 0.3, fixed dt = 1e-6 s, gravity 9.81 m/s², no local
//   damping, no dashpots, clump mass by summing the balls (mode "sum": what LAMMPS
//   fix rigid/small and YADE appendClumped compute), density 2600 kg/m³.
//
// Our contacts put the two entities' springs in series (PFC), so balls and walls
// are given 2 × 5.08e9 N/m each: 1.016e10·1.016e10/(2·1.016e10) = 5.08e9 per contact.
// The conventions of all three codes, checked: docs/PERFORMANCE.md, "Peers".
#pragma once

#include <iosfwd>

#include "cases/packing_file.hpp"
#include "engine/clump_mass.hpp"
#include "engine/rigid_rotation.hpp"
#include "engine/simulation.hpp"

namespace ballast {

struct BenchBedOptions {
  double length = 0.7, width = 0.3, height = 0.45;  // m, box (open top)
  double contact_stiffness = 5.08e9;                // N/m, kn = ks of every contact
  double friction = 0.3;
  double dt = 1e-6;            // s, fixed
  double density = 2600;       // kg/m³
  double gravity = 9.81;       // m/s², along −z
  double local_damping = 0.0;  // PFC α; 0 in the benchmark (the convention checks settle with it)
  MassMode mass_mode = MassMode::kSum;
  // Both peers integrate a clump's full rigid-body rotation (LAMMPS rigid/small:
  // Richardson iteration on the quaternion; YADE: exact aspherical rotation), so
  // the benchmark does too by default.
  RotationIntegrator rotation = RotationIntegrator::kFull;
  // SimulationSettings::skip_far_candidates; false measures what the skip saves, in
  // one binary, with the same bits.
  bool skip_far_candidates = true;
  // SimulationSettings::simd_lanes: 0 measures what the SIMD sphere kernel saves, in
  // one binary, with the same bits.
  int simd_lanes = -1;
  // Keep the file's numbering even where sorting pays (Simulation::sort_bodies_spatially):
  // measures what the sort buys.
  bool keep_file_order = false;
  // SimulationSettings::energy_ledger. Off: the benchmark reports kinetic energy only,
  // and the peers book no energy either; on measures what the ledger costs.
  bool energy_ledger = false;
  std::ostream* log = nullptr;  // dt report and warnings
};

// The entity stiffness that gives `contact` N/m per contact in series with an equal
// one: 2 × contact.
inline double entity_stiffness_for_contact(double contact) {
  return 2.0 * contact;
}

Simulation make_bench_bed(const Packing& packing, const BenchBedOptions& o);

// What the three codes compare after the same number of steps. Forces are over the
// contacts touching now (overlap > 0), ball–ball between different bodies only.
struct ContactForceMeans {
  long count = 0;
  double normal = 0.0;      // N, mean kn·overlap (the elastic normal force)
  double tangential = 0.0;  // N, mean |shear force|
};

struct BenchBedPhysics {
  ContactForceMeans ball_ball, ball_wall, all;
  double kinetic_translational = 0.0;  // J, Σ ½ m v² (half-step velocities)
  double kinetic_rotational = 0.0;     // J, Σ ½ ω·I ω
  double kinetic() const { return kinetic_translational + kinetic_rotational; }
};

BenchBedPhysics measure_bench_bed(const Simulation& sim);

}  // namespace ballast
