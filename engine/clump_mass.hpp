// Mass properties of a clump and its principal frame (Lu & McDowell 2007 eqs 10-15,
// and uniform density over the union of the balls). See MassMode in
// engine/clump_template.hpp and docs/CLUMPS.md, "Mass modes".
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "engine/clump_generator.hpp"
#include "engine/clump_template.hpp"
#include "engine/types.hpp"

namespace ballast {

struct ClumpMassOptions {
  MassMode mode = MassMode::kUniform;
  double density = 2600.0;  // rho0, kg/m³ (the paper's ballast)
  // kUniform: requested relative error of the volume and of every principal moment,
  // in [1e-5, 0.1] (see engine/ball_union_integral.hpp).
  double accuracy = 0.005;
};

// Throws std::invalid_argument naming the field, its value and what is allowed.
void validate_mass_options(const ClumpMassOptions& options);

// "sum", "paper", "uniform".
const char* mass_mode_name(MassMode mode);
// Inverse of mass_mode_name; throws std::invalid_argument listing the names.
MassMode parse_mass_mode(std::string_view name);

// Mass, centre of mass and inertia tensor in the frame of the input centres.
struct MassProperties {
  double mass = 0.0;            // kg
  Vec3 centre = Vec3::Zero();   // m
  Mat3 inertia = Mat3::Zero();  // kg·m² about the centre of mass
  double volume = 0.0;          // m³ the mass stands for (see ClumpTemplate::volume)
  double density = 0.0;         // kg/m³ the balls carry
  double relative_error = 0.0;  // kUniform only: the integrator's estimate
};

// Eqs 12-15: every ball a solid sphere of the given density, overlaps counted twice,
// I = Σ m_p [(2/5) R_p² 𝟙 + |d_p|² 𝟙 - d_p d_pᵀ], d_p = x_p - x_G.
MassProperties summed_mass_properties(const std::vector<Vec3>& centres,
                                      const std::vector<double>& radii, double density);

// All three modes. clump_volume is V_clump of eq 10 (kPaper only), m³.
MassProperties clump_mass_properties(const std::vector<Vec3>& centres,
                                     const std::vector<double>& radii,
                                     const ClumpMassOptions& options, double clump_volume);

// Principal frame: eigen-decomposition of the inertia tensor, moments ascending, axes
// right-handed with signs fixed (largest component of the first two axes positive)
// so that the same input always gives the same frame.
ClumpTemplate to_principal_frame(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                                 const MassProperties& mp, MassMode mode);

// The template of a generated clump; kPaper takes V_clump as the volume of the
// nominal sphere, as the paper does.
ClumpTemplate make_clump_template(const ClumpGeometry& geometry, const ClumpMassOptions& options);

}  // namespace ballast
