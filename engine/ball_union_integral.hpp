// Volume, centroid and second moments of the union of a set of balls (overlaps
// counted once), for uniform-density clumps. PFC3D 3.x and the paper sum ball masses
// instead and so count every overlap twice.
//
// Method (docs/CLUMPS.md, "Uniform mode"): along z the integral is exact: at a point
// (x, y) each ball covers the chord [z_i - h_i, z_i + h_i], the chords are merged and
// ∫dz, ∫z dz, ∫z² dz over their union are closed-form. Over (x, y) a globally adaptive
// quadtree midpoint rule is used. Each leaf square carries an error estimate:
//  * |fine - coarse| / 3, fine being the 2x2 rule on its quarters (returned) and
//    coarse the 1-point rule (Richardson for a second-order rule), for the volume and
//    for the spectral norm of the unit-density inertia tensor (Weyl: a bound on the
//    change of every principal moment);
//  * plus, for a ball whose disk meets the square but holds none of the 5 sample
//    points, a bound on what it can add there (sample points cannot see it).
// The leaf with the largest estimate is split until
//     Σ err_V <= accuracy · V   and   Σ err_I <= accuracy · I_min,
// I_min being the smallest principal moment. Cells that no disk meets are exactly
// empty. tests/test_clump_mass.cpp checks that the actual errors stay below the
// estimate against closed forms (sphere, lens, dumbbell) and a 50x finer reference.
#pragma once

#include <vector>

#include "engine/types.hpp"

namespace ballast {

struct BallUnionMoments {
  double volume = 0.0;                // m³
  Vec3 centroid = Vec3::Zero();       // m, in the frame of the input centres
  Mat3 second_moment = Mat3::Zero();  // ∫(x-g)(x-g)ᵀ dV about the centroid, m⁵
  double volume_error = 0.0;          // estimated bound on |volume error|, m³
  double inertia_error = 0.0;         // estimated bound on ‖error of unit_inertia()‖_2, m⁵
  long evaluations = 0;               // columns evaluated (a measure of the work)
  bool converged = false;             // false when the cell budget ran out first

  // Inertia tensor per unit density about the centroid: ∫(|r|²𝟙 - r rᵀ) dV, m⁵.
  Mat3 unit_inertia() const { return second_moment.trace() * Mat3::Identity() - second_moment; }
};

// accuracy: requested relative error, in [1e-5, 0.1]; radii > 0 and centres finite.
// Throws std::invalid_argument on bad input.
BallUnionMoments integrate_ball_union(const std::vector<Vec3>& centres,
                                      const std::vector<double>& radii, double accuracy);

// True when some pair of balls overlaps (centre distance < sum of radii).
bool balls_overlap(const std::vector<Vec3>& centres, const std::vector<double>& radii);

// What clumps use: closed form, with zero error, when no two balls overlap (a one-ball
// clump, for instance), integrate_ball_union otherwise.
BallUnionMoments ball_union_moments(const std::vector<Vec3>& centres,
                                    const std::vector<double>& radii, double accuracy);

}  // namespace ballast
