// A sphere resting on a plane under gravity: the overlap must be m·g/k with k the
// ball and wall stiffness in series (PFC), here for the paper's rubber base.
#include <gtest/gtest.h>

#include "cases/box_test.hpp"
#include "test_helpers.hpp"

using namespace ballast;

TEST(StaticOverlap, SphereOnRubberBaseSinksByWeightOverSeriesStiffness) {
  const double r = 0.5 * box_test::kSphereDiameter, rho = box_test::kDensity, g = 9.81;
  SimulationSettings s = scenes::bare_settings();
  s.gravity = Vec3(0, 0, -g);
  s.local_damping = 0.7;
  Simulation sim(s);
  const Index mat = sim.add_material(box_test::ballast_material());
  sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), box_test::rubber_base()));
  const Index b = sim.add_sphere(Vec3(0, 0, r + 0.001), r, rho, mat);
  sim.run(200000);
  const double k = series_stiffness(box_test::kBallStiffness, box_test::kRubberStiffness);
  EXPECT_NEAR(k, 2.5387e6, 0.0001e6);  // the "about 2.54e6 N/m" of the issue
  const double expected = scenes::sphere_mass(r, rho) * g / k;
  const double overlap = r - sim.bodies().position[b].z();
  EXPECT_NEAR(overlap, expected, 1e-3 * expected);
  EXPECT_LT(sim.bodies().velocity[b].norm(), 1e-6);
}

TEST(StaticOverlap, BallBallSeriesStiffnessIsHalfTheBallStiffness) {
  EXPECT_DOUBLE_EQ(series_stiffness(5.08e9, 5.08e9), 2.54e9);
}
