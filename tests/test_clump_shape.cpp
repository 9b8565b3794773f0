// Shape statistics of clumps against closed forms: a sphere, two overlapping spheres,
// nested and duplicate balls, a dumbbell; and the sample summary.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "cases/clump_presets.hpp"
#include "engine/clump_batch.hpp"
#include "engine/clump_mass.hpp"
#include "engine/clump_shape.hpp"
#include "test_helpers.hpp"

namespace ballast {
namespace {

// Relative. With the default 4096 points the worst error over 44 distances of this
// pair is 0.14% (docs/CLUMPS.md); 0.3% leaves room for other orientations.
constexpr double kAreaTolerance = 0.003;

ClumpTemplate uniform_template(const std::vector<Vec3>& centres, const std::vector<double>& radii) {
  const ClumpMassOptions o;  // uniform, 0.5%
  return to_principal_frame(centres, radii, clump_mass_properties(centres, radii, o, 0.0), o.mode);
}

// Area of the union of two balls: each sphere minus the cap inside the other.
double two_ball_union_area(double r1, double r2, double d) {
  const double x1 = (d * d + r1 * r1 - r2 * r2) / (2 * d);  // centre 1 to the cut plane
  const double cap1 = r1 - x1, cap2 = r2 - (d - x1);        // cap heights
  return 4 * kPi * (r1 * r1 + r2 * r2) - 2 * kPi * (r1 * cap1 + r2 * cap2);
}

TEST(ClumpShape, OneSphereHasSphericityOneAndEqualExtents) {
  const double r = 0.018;
  const ClumpShape s =
      measure_clump_shape(uniform_template({Vec3(0.1, 0.2, 0.3)}, {r}), r, ClumpShapeOptions{});
  EXPECT_EQ(s.balls, 1);
  EXPECT_NEAR(s.surface_area, 4 * kPi * r * r, 1e-12 * r * r);  // no neighbour: exact
  EXPECT_NEAR(s.union_volume, scenes::sphere_volume(r), 0.005 * scenes::sphere_volume(r));
  EXPECT_NEAR(s.sphericity, 1.0, 0.005);
  EXPECT_NEAR(s.a, 2 * r, 1e-15);
  EXPECT_NEAR(s.c, 2 * r, 1e-15);
  EXPECT_NEAR(s.elongation, 1.0, 1e-12);
  EXPECT_NEAR(s.flatness, 1.0, 1e-12);
  EXPECT_NEAR(s.volume_ratio, 1.0, 0.005);  // virtual sphere = the ball itself
}

TEST(ClumpShape, TwoOverlappingSpheresMatchTheCapFormula) {
  const double r1 = 0.02, r2 = 0.012;
  for (double d : {0.01, 0.018, 0.026}) {
    const Vec3 axis = Vec3(1.0, 0.3, -0.2).normalized();
    const double area = union_surface_area({Vec3::Zero(), d * axis}, {r1, r2}, 4096);
    const double exact = two_ball_union_area(r1, r2, d);
    EXPECT_NEAR(area / exact, 1.0, kAreaTolerance) << "d = " << d;
  }
}

TEST(ClumpShape, NestedAndDuplicateBallsAddNoSurface) {
  const double r = 0.02;
  const double one = 4 * kPi * r * r;
  // A small ball wholly inside the big one, and an exact duplicate of the big one.
  EXPECT_NEAR(union_surface_area({Vec3::Zero(), Vec3(0.005, 0, 0)}, {r, 0.01}, 4096), one,
              1e-12 * one);
  EXPECT_NEAR(union_surface_area({Vec3::Zero(), Vec3::Zero()}, {r, r}, 4096), one, 1e-12 * one);
}

TEST(ClumpShape, DumbbellDimensionsAreAlongItsPrincipalAxes) {
  const double r = 0.01, h = 0.015;  // two balls apart, centres at ±h on a tilted axis
  const Vec3 axis = Vec3(0.3, -1.0, 0.5).normalized();
  // Sum mode: exact for balls that do not overlap, so the frame is exact too.
  const std::vector<Vec3> centres = {h * axis, -h * axis};
  const ClumpTemplate t = to_principal_frame(
      centres, {r, r}, summed_mass_properties(centres, {r, r}, 2600.0), MassMode::kSum);
  const ClumpShape s = measure_clump_shape(t, h + r, ClumpShapeOptions{});
  EXPECT_NEAR(s.a, 2 * (h + r), 1e-12);
  EXPECT_NEAR(s.b, 2 * r, 1e-12);
  EXPECT_NEAR(s.c, 2 * r, 1e-12);
  EXPECT_NEAR(s.elongation, r / (h + r), 1e-12);
  EXPECT_NEAR(s.flatness, 1.0, 1e-12);
  // Apart, the union is the two spheres: exact area, sphericity of two separate balls.
  EXPECT_NEAR(s.surface_area, 8 * kPi * r * r, 1e-12 * r * r);
  const double v = 8.0 / 3.0 * kPi * r * r * r;
  EXPECT_NEAR(s.sphericity, std::cbrt(kPi) * std::pow(6 * v, 2.0 / 3.0) / (8 * kPi * r * r), 0.005);
}

TEST(ClumpShape, SphericityIsBelowOneAndTheSameOnOneAndTwoThreads) {
  const ClumpPreset preset = load_clump_preset("table2/sample2");
  const ClumpMassOptions o;
  const std::vector<ClumpTemplate> clumps = generate_clump_templates(preset.params, o, 40, 3);
  test_support::ScopedThreads threads(1);
  const std::vector<ClumpShape> one =
      measure_clump_shapes(clumps, virtual_sphere_radius(preset.params), ClumpShapeOptions{});
  threads.set(2);
  const std::vector<ClumpShape> two =
      measure_clump_shapes(clumps, virtual_sphere_radius(preset.params), ClumpShapeOptions{});
  for (std::size_t i = 0; i < clumps.size(); ++i) {
    EXPECT_EQ(one[i].surface_area, two[i].surface_area);
    EXPECT_EQ(one[i].union_volume, two[i].union_volume);
    // A union of several overlapping balls is less spherical than a sphere, and its
    // extents are ordered and bounded by the virtual sphere.
    if (one[i].balls > 1) {
      EXPECT_LT(one[i].sphericity, 1.0);
    }
    EXPECT_GE(one[i].a, one[i].b);
    EXPECT_GE(one[i].b, one[i].c);
    EXPECT_LE(one[i].a, 2 * virtual_sphere_radius(preset.params) * (1 + 1e-12));
    EXPECT_LT(one[i].volume_ratio, 1.0);
  }
}

TEST(ClumpShape, SummaryHasMeanMinMaxAndSpread) {
  const StatSummary s = summarize({3.0, 1.0, 2.0, 6.0});
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 6.0);
  EXPECT_DOUBLE_EQ(s.stddev, std::sqrt(14.0 / 3.0));  // Σ(x - 3)² = 0 + 4 + 1 + 9
  std::vector<ClumpShape> shapes(2);
  shapes[0].balls = 7;
  shapes[1].balls = 33;
  const ClumpShapeSummary sum = summarize_shapes(shapes);
  EXPECT_EQ(sum.count, 2);
  EXPECT_DOUBLE_EQ(sum.balls.mean, 20.0);
  EXPECT_DOUBLE_EQ(sum.balls.min, 7.0);
  EXPECT_DOUBLE_EQ(sum.balls.max, 33.0);
}

}  // namespace
}  // namespace ballast
