// A sphere launched sliding without spin on a frictional plane: friction slows it
// and spins it up until it rolls, at v = 5/7·v0 (solid sphere, I = 2/5·m·r²).
#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.hpp"

using namespace ballast;

TEST(Sliding, SlipStopsAtFiveSeventhsOfLaunchSpeed) {
  const double r = 0.02, rho = 2600.0, g = 9.81, k = 1e7, mu = 0.3, v0 = 1.0;
  SimulationSettings s = scenes::bare_settings(5.0);
  s.gravity = Vec3(0, 0, -g);
  s.fixed_dt = 1e-6;
  Simulation sim(s);
  const Index mat = sim.add_material({2 * k, 2 * k, mu});
  sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), {2 * k, 2 * k, mu}));
  const double m = scenes::sphere_mass(r, rho);
  // Start at the static overlap so the normal force is m·g from the first step.
  const Index b = sim.add_sphere(Vec3(-2.0, 0, r - m * g / k), r, rho, mat);
  sim.set_body_velocity(b, Vec3(v0, 0, 0));
  // Sliding lasts t = 2·v0/(7·mu·g) ≈ 0.097 s; run twice that.
  const double t_slide = 2 * v0 / (7 * mu * g);
  sim.run(static_cast<long>(2 * t_slide / 1e-6));
  const double v = sim.bodies().velocity[b].x();
  EXPECT_NEAR(v, 5.0 / 7.0 * v0, 0.01 * 5.0 / 7.0 * v0);
  // Rolling without slip: ω·r = v.
  EXPECT_NEAR(sim.bodies().angular_velocity[b].y() * r, v, 0.01 * v);
}

// The paper raises friction from 0.3 (compaction) to 0.5 (loading) mid-run. While a
// sphere slips, its deceleration is exactly mu·g, so the change shows at once.
TEST(Sliding, FrictionChangeTakesEffectMidRun) {
  const double r = 0.02, rho = 2600.0, g = 9.81, k = 1e7, v0 = 2.0, dt = 1e-6;
  SimulationSettings s = scenes::bare_settings(5.0);
  s.gravity = Vec3(0, 0, -g);
  s.fixed_dt = dt;
  Simulation sim(s);
  const Index mat = sim.add_material({2 * k, 2 * k, 0.3});
  sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), {2 * k, 2 * k, 0.3}));
  const double m = scenes::sphere_mass(r, rho);
  const Index b = sim.add_sphere(Vec3(-2.0, 0, r - m * g / k), r, rho, mat);
  sim.set_body_velocity(b, Vec3(v0, 0, 0));
  sim.run(50000);  // 0.05 s at mu = 0.3 (slip would last 2·v0/(7·0.3·g) = 0.19 s)
  const double v1 = sim.bodies().velocity[b].x();
  EXPECT_NEAR(v1, v0 - 0.3 * g * 0.05, 0.01 * 0.3 * g * 0.05);
  sim.set_all_friction(0.5);
  sim.run(50000);  // 0.05 s at mu = 0.5, still slipping
  const double v2 = sim.bodies().velocity[b].x();
  EXPECT_NEAR(v1 - v2, 0.5 * g * 0.05, 0.01 * 0.5 * g * 0.05);
}
