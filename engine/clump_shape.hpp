// Shape statistics of clumps (docs/CLUMPS.md, "Shape statistics"): size, surface,
// sphericity and principal dimensions of the union of the balls, per clump and
// aggregated over a sample.
#pragma once

#include <vector>

#include "engine/clump_template.hpp"
#include "engine/types.hpp"

namespace ballast {

struct ClumpShapeOptions {
  // Relative accuracy of the union volume when the template does not carry it
  // (engine/ball_union_integral.hpp), in [1e-5, 0.1].
  double volume_accuracy = 0.005;
  // Fibonacci points on the largest ball; smaller balls get proportionally fewer
  // (same points per unit area, at least 64). 4096 keeps the area within ~0.2%
  // (tests/test_clump_shape.cpp).
  int surface_points = 4096;
};

struct ClumpShape {
  int balls = 0;
  double union_volume = 0.0;  // m³
  double surface_area = 0.0;  // m², of the union
  double sphericity = 0.0;    // Wadell: π^(1/3) (6V)^(2/3) / A, 1 for a sphere
  // Extents of the union along the principal axes, sorted a >= b >= c, m.
  double a = 0.0, b = 0.0, c = 0.0;
  double elongation = 0.0;    // b / a
  double flatness = 0.0;      // c / b
  double volume_ratio = 0.0;  // union volume / virtual-sphere volume
};

// Area of the surface of the union of balls: each sphere's area times the fraction of
// a spherical Fibonacci point set on it that no other ball covers. Identical balls
// are counted once. m².
double union_surface_area(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                          int points_on_largest);

// Statistics of one clump. The union volume is taken from the template when it is
// a kUniform one and integrated otherwise. virtual_radius: Rv, m.
ClumpShape measure_clump_shape(const ClumpTemplate& clump, double virtual_radius,
                               const ClumpShapeOptions& options);

// Statistics of many clumps, in parallel (OpenMP), each clump written to its own slot.
std::vector<ClumpShape> measure_clump_shapes(const std::vector<ClumpTemplate>& clumps,
                                             double virtual_radius,
                                             const ClumpShapeOptions& options);

// Mean, minimum and maximum of one statistic over a sample.
struct StatSummary {
  double mean = 0.0, min = 0.0, max = 0.0;
  double stddev = 0.0;  // sample standard deviation (n - 1), 0 for one value
};
// Accumulates in index order, so the result does not depend on thread count.
StatSummary summarize(const std::vector<double>& values);

struct ClumpShapeSummary {
  int count = 0;
  StatSummary balls, union_volume, surface_area, sphericity, a, b, c, elongation, flatness,
      volume_ratio;
};
ClumpShapeSummary summarize_shapes(const std::vector<ClumpShape>& shapes);

}  // namespace ballast
