// Porosity of a packing, two ways (docs/POROSITY.md):
//
//  * measurement sphere (PFC's "measurement sphere"): the solid volume inside a
//    sphere is the sum over balls of the exact ball–sphere intersection volume, and
//        n = 1 − Σ_i V(ball_i ∩ sphere) / V_sphere.
//    Exact for balls that do not overlap. The balls of one rigid clump overlap each
//    other by design, and the sum counts every such overlap twice (as PFC does), so
//    on a bed of clumps it reads too little porosity.
//  * grid (Lu & McDowell 2007, section 3.3: "a 3-D grid of small cubes, each of side
//    0.005 m, in the column directly below the sleeper"): a cube is solid when its
//    centre lies inside any ball, and n = void cubes / all cubes. Overlaps are counted
//    once; the price is a discretisation error that shrinks with the cube side.
//
// Both are deterministic: the sphere sums balls serially in index order, the grid
// counts integers, so neither depends on the number of OpenMP threads.
#pragma once

#include <array>
#include <cstdint>

#include "engine/ball_store.hpp"
#include "engine/types.hpp"

namespace ballast {

// Exact volume (units of r³) of the intersection of a ball of radius r and a sphere
// of radius R whose centres are d apart:
//   d >= R + r          → 0 (disjoint or touching);
//   d <= |R − r|        → (4/3)π min(r, R)³ (the smaller one lies inside);
//   otherwise the lens  V = π (R + r − d)² (d² + 2dr − 3r² + 2dR + 6rR − 3R²) / (12 d)
// (sum of the two spherical caps cut by the plane of the intersection circle; e.g.
// Weisstein, "Sphere-Sphere Intersection", MathWorld). Symmetric in r and R and
// continuous in d. Requires r > 0, R > 0, d >= 0, all finite (throws SetupError).
double ball_sphere_intersection_volume(double r, double R, double d);

struct MeasurementSphereResult {
  double porosity = 1.0;      // 1 − solid_volume / volume
  double solid_volume = 0.0;  // m³, Σ V(ball ∩ sphere): clump overlaps counted twice
  double volume = 0.0;        // m³, (4/3)π radius³
  Index balls_inside = 0;     // balls that meet the sphere's interior (wholly or in part)
  Index balls_cut = 0;        // of those, the balls the sphere's surface cuts through
};

// The measurement-sphere estimator above over every ball of `balls`. O(number of
// balls): one sphere is cheap; a study with many spheres should bin balls first.
// radius > 0 and centre finite (SetupError otherwise). Serial, so the floating-point
// sum is the same on any number of threads.
MeasurementSphereResult measurement_sphere_porosity(const BallStore& balls, const Vec3& centre,
                                                    double radius);

struct GridPorosityResult {
  double porosity = 1.0;              // void_cubes / total_cubes
  std::int64_t solid_cubes = 0;       // cubes whose centre lies inside at least one ball
  std::int64_t total_cubes = 0;       // cubes[0] · cubes[1] · cubes[2]
  std::array<int, 3> cubes{1, 1, 1};  // cubes per axis
  Vec3 cube_size = Vec3::Zero();      // m, the edges actually used (see below)
  double solid_volume() const { return static_cast<double>(solid_cubes) * cube_size.prod(); }
};

// The grid estimator above over the box [lo, hi]. Along each axis a the box holds
// n_a = max(1, round((hi_a − lo_a) / cube_side)) cubes, and their edge is stretched or
// shrunk to (hi_a − lo_a) / n_a so that they tile the box exactly: the porosity is
// always that of the box asked for, and a box that is not a multiple of cube_side
// gets edges at most side/(2 n_a) off (reported in cube_size); a box thinner than half
// a side gets one cube as thick as the box. A centre counts as solid when its distance
// to a ball centre is strictly less than that ball's radius.
//
// Work: balls are binned by the layers of cubes (along z) they reach, and each layer
// is rasterised on its own, O(balls + cubes + Σ cubes in each ball's bounding box).
// Layers run in parallel with OpenMP; counts are integers, so the result does not
// depend on the thread count. Requires cube_side > 0, lo and hi finite with hi > lo
// on each axis, at most 2^31 cubes, finite ball positions and radii > 0 (SetupError
// otherwise).
GridPorosityResult grid_porosity(const BallStore& balls, const Vec3& lo, const Vec3& hi,
                                 double cube_side);

}  // namespace ballast
