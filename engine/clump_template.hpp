// A rigid clump ready to be placed in a simulation: its balls in the body's principal
// frame and its mass properties. This is what the engine consumes to create a body
// (BodyStore::add takes mass and principal_inertia; BallStore::add takes each offset).
//
// Produced by make_clump_template (engine/clump_mass.hpp) from the raw geometry of
// generate_clump (engine/clump_generator.hpp). Plain data: no invariants are enforced
// here, the producer guarantees them:
//  * offsets are relative to the centre of mass, expressed in the principal frame;
//  * the principal frame is right-handed and principal_inertia is ascending;
//  * generation frame position x_gen = generation_centre + generation_rotation * offset.
#pragma once

#include <vector>

#include "engine/types.hpp"

namespace ballast {

// How mass and inertia are attributed to the balls of a clump (see docs/CLUMPS.md).
enum class MassMode {
  // PFC3D 3.x: every ball is a solid sphere of density rho0, overlaps counted twice
  // (eqs 12-15 of Lu & McDowell 2007 with the material density).
  kSum,
  // Lu & McDowell 2007 eqs 10-15: like kSum but with the scaled density
  // rho_m = V_clump·rho0 / ΣV_i (eq 10), V_clump = volume of the nominal sphere.
  kPaper,
  // Uniform density rho0 over the union of the balls, by numerical integration
  // (engine/ball_union_integral.hpp). The physically consistent choice.
  kUniform,
};

struct ClumpTemplate {
  // Ball centres relative to the centre of mass, in the principal frame, m.
  std::vector<Vec3> offsets;
  // Ball radii, m, same order as offsets.
  std::vector<double> radii;

  double mass = 0.0;                      // kg
  Vec3 principal_inertia = Vec3::Zero();  // kg·m² about the centre of mass, ascending
  // Volume the mass stands for, m³: ΣV_i (kSum), the nominal sphere (kPaper) or the
  // union of the balls (kUniform).
  double volume = 0.0;
  // Density the balls carry, kg/m³: rho0 for kSum and kUniform, rho_m for kPaper.
  double density = 0.0;
  MassMode mass_mode = MassMode::kUniform;
  // kUniform only: the integrator's estimate of the relative error of the volume and
  // of the principal moments (see docs/CLUMPS.md); 0 for the closed-form modes.
  double integration_error = 0.0;

  // Where the body sat in the frame it was generated in (central ball at the origin):
  // centre of mass, m, and the rotation whose columns are the principal axes.
  Vec3 generation_centre = Vec3::Zero();
  Mat3 generation_rotation = Mat3::Identity();

  int ball_count() const { return static_cast<int>(radii.size()); }
};

}  // namespace ballast
