// Walls: servo force control, prescribed motion and the solid box's closest-point
// contact.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/errors.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

// A sphere between a fixed base and a servo-driven lid; no gravity.
struct Sandwich {
  Simulation sim;
  Index ball, lid;
};

Sandwich sandwich(std::function<double(double)> target) {
  SimulationSettings s = scenes::bare_settings();
  s.local_damping = 0.7;
  Sandwich out{Simulation(s), 0, 0};
  const Material m{1e8, 1e8, 0.3};
  const double r = 0.02;
  const Index mat = out.sim.add_material(m);
  out.sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), m));
  out.lid = out.sim.add_wall(scenes::plane_wall(Vec3(0, 0, 2 * r + 0.002), -Vec3::UnitZ(), m));
  out.ball = out.sim.add_sphere(Vec3(0, 0, r), r, 2600, mat);
  Servo servo;
  servo.walls = {out.lid};
  servo.axis = -Vec3::UnitZ();
  servo.target_force = std::move(target);
  servo.max_speed = 0.5;
  out.sim.add_servo(servo);
  return out;
}

}  // namespace

TEST(Walls, ServoHoldsTheTargetForce) {
  const double target = 500.0;  // N
  Sandwich w = sandwich([=](double) { return target; });
  w.sim.run(60000);
  const Servo& s = w.sim.servos()[0];
  EXPECT_NEAR(s.measured_force, target, 1e-3 * target);
  // The lid's reaction and the base's must both equal the load.
  EXPECT_NEAR(w.sim.wall_force(w.lid).z(), target, 1e-3 * target);
  EXPECT_NEAR(w.sim.wall_force(0).z(), -target, 1e-3 * target);
}

TEST(Walls, ReleasedServoLeavesItsWallStandingUnderTheLoadItHeld) {
  const double target = 500.0;  // N
  Sandwich w = sandwich([=](double) { return target; });
  w.sim.run(60000);
  const double z = w.sim.walls()[w.lid].point.z();
  w.sim.release_servo(0);
  EXPECT_TRUE(w.sim.servos().empty());
  EXPECT_EQ(w.sim.walls()[w.lid].velocity, Vec3::Zero());
  // Held still, the lid keeps the ball squeezed: its force stays near the target
  // (the ball settles a little without the servo's correction) and the lid does
  // not move, where a servo left running would follow any change of the load.
  w.sim.run(20000);
  EXPECT_EQ(w.sim.walls()[w.lid].point.z(), z);
  EXPECT_NEAR(w.sim.wall_force(w.lid).z(), target, 0.02 * target);
  EXPECT_THROW(w.sim.release_servo(0), SetupError);
}

TEST(Walls, SinusoidalLoadRunsFromMinimumToMaximumAndBack) {
  const auto f = sinusoidal_load(3e3, 40e3, 3.0, 0.0);
  EXPECT_NEAR(f(0.0), 3e3, 1e-9);
  EXPECT_NEAR(f(1.0 / 6.0), 40e3, 1e-6);
  EXPECT_NEAR(f(1.0 / 3.0), 3e3, 1e-6);
  EXPECT_NEAR(f(1.0 / 12.0), 21.5e3, 1e-6);
}

TEST(Walls, ServoFollowsASlowSineWithinOnePercentOfItsRange) {
  // 200 N to 600 N at 20 Hz: slow compared with the contact's ~500 Hz.
  Sandwich w = sandwich(sinusoidal_load(200.0, 600.0, 20.0, 0.0));
  w.sim.run(20000);  // settle onto the curve
  double worst = 0.0;
  for (int k = 0; k < 20000; ++k) {
    w.sim.step();
    const Servo& s = w.sim.servos()[0];
    worst = std::max(worst, std::abs(s.measured_force - s.target_now));
  }
  EXPECT_LT(worst, 0.01 * 400.0);
}

TEST(Walls, PrescribedVelocityMovesTheWallExactly) {
  SimulationSettings s = scenes::bare_settings();
  s.fixed_dt = 1e-5;
  Simulation sim(s);
  const Index mat = sim.add_material({1e6, 1e6, 0.0});
  sim.add_sphere(Vec3(0.5, 0.5, 0.5), 0.01, 2600, mat);
  const Index w = sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), {1e6, 1e6, 0}));
  sim.set_wall_velocity(w, Vec3(0, 0, 0.25));
  sim.run(1000);
  EXPECT_NEAR(sim.walls()[w].point.z(), 0.25 * 1000 * 1e-5, 1e-12);
}

// Three spheres at rest on a fixed base under gravity, beside a fixed side wall.
// With `moving_far_wall`, a wall far from every ball moves, so that the engine sums
// every wall's force each step instead of when asked for.
Simulation resting_spheres(bool moving_far_wall) {
  SimulationSettings s = scenes::bare_settings();
  s.gravity = Vec3(0, 0, -9.81);
  s.local_damping = 0.7;
  s.fixed_dt = 1e-5;  // the far wall's extra neighbour builds then change no bit
  Simulation sim(s);
  const Material m{1e7, 1e7, 0.3};
  const Index mat = sim.add_material(m);
  sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), m));
  sim.add_wall(scenes::plane_wall(Vec3(-0.02, 0, 0), Vec3::UnitX(), m));
  const Index far = sim.add_wall(scenes::plane_wall(Vec3(0.9, 0, 0), -Vec3::UnitX(), m));
  if (moving_far_wall) sim.set_wall_velocity(far, Vec3(-1e-3, 0, 0));
  for (int k = 0; k < 3; ++k) sim.add_sphere(Vec3(0.05 * k, 0, 0.02), 0.02, 2600, mat);
  return sim;
}

TEST(Walls, AFixedWallsForceIsTheSameSummedEachStepOrWhenAskedFor) {
  Simulation asked = resting_spheres(false), summed = resting_spheres(true);
  asked.run(20000);
  summed.run(20000);
  double weight = 0.0;
  for (Index b = 0; b < asked.bodies().size(); ++b) weight += 9.81 * asked.bodies().mass[b];
  for (Index w = 0; w < 3; ++w)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(asked.wall_force(w)[k], summed.wall_force(w)[k]) << "wall " << w << " axis " << k;
  // At rest the base carries the weight; the side wall and the far wall nothing.
  EXPECT_NEAR(-asked.wall_force(0).z(), weight, 1e-3 * weight);
  EXPECT_NEAR(asked.wall_force(1).norm(), 0.0, 1e-3 * weight);
  EXPECT_EQ(asked.wall_force(2).norm(), 0.0);
  EXPECT_THROW(asked.wall_force(3), SetupError);
}

TEST(Walls, SolidBoxTouchesAtFacesEdgesAndCorners) {
  Wall box;
  box.shape = WallShape::Box;
  box.lo = Vec3(0, 0, 0);
  box.hi = Vec3(1, 1, 1);
  const double r = 0.1;
  // Face: below the bottom face.
  WallTouch t = touch_wall(box, Vec3(0.5, 0.5, -0.05), r);
  EXPECT_NEAR(t.overlap, 0.05, 1e-15);
  EXPECT_TRUE(t.normal.isApprox(-Vec3::UnitZ()));
  // Edge: diagonal from the bottom x-edge; one contact along the diagonal.
  const double d = 0.08;
  t = touch_wall(box, Vec3(-d / std::sqrt(2.0), 0.5, -d / std::sqrt(2.0)), r);
  EXPECT_NEAR(t.overlap, r - d, 1e-15);
  EXPECT_TRUE(t.normal.isApprox(Vec3(-1, 0, -1).normalized()));
  // Corner.
  t = touch_wall(box, Vec3(1.05, 1.05, 1.05), r);
  EXPECT_NEAR(t.overlap, r - std::sqrt(3.0) * 0.05, 1e-15);
  // Centre inside the box: pushed out through the nearest face.
  t = touch_wall(box, Vec3(0.5, 0.98, 0.5), r);
  EXPECT_TRUE(t.normal.isApprox(Vec3::UnitY()));
  EXPECT_NEAR(t.overlap, r + 0.02, 1e-12);
}

TEST(Walls, RoundedBoxTouchesAsItsCoreGrownByTheEdgeRadius) {
  Wall box;
  box.shape = WallShape::Box;
  box.lo = Vec3(0, 0, 0);
  box.hi = Vec3(1, 1, 1);
  box.edge_radius = 0.2;  // core [0.2, 0.8]^3
  const double r = 0.1;
  // Under the middle of a face, rounding changes nothing.
  WallTouch t = touch_wall(box, Vec3(0.5, 0.5, -0.05), r);
  EXPECT_NEAR(t.overlap, 0.05, 1e-15);
  EXPECT_TRUE(t.normal.isApprox(-Vec3::UnitZ()));
  EXPECT_NEAR(t.point.z(), 0.0, 1e-15);
  // Off the lower x-edge along the diagonal: the sharp box's edge is 0.08 from the
  // centre (a 0.02 overlap), the rounded surface 0.08 + (√2 − 1)·0.2 = 0.163 away,
  // so the ball no longer touches.
  const double d = 0.08;
  const Vec3 off_edge(-d / std::sqrt(2.0), 0.5, -d / std::sqrt(2.0));
  t = touch_wall(box, off_edge, r);
  EXPECT_NEAR(t.overlap, r - (d + (std::sqrt(2.0) - 1.0) * 0.2), 1e-15);
  EXPECT_LT(t.overlap, 0.0);
  EXPECT_TRUE(t.normal.isApprox(Vec3(-1, 0, -1).normalized()));
  // On the rounded edge the contact lies on the cylinder of radius 0.2 about the core
  // edge, and the normal points from that edge to the centre.
  const Vec3 on_arc = Vec3(0.2, 0.5, 0.2) + (0.2 + 0.05) * Vec3(-1, 0, -1).normalized();
  t = touch_wall(box, on_arc, r);
  EXPECT_NEAR(t.overlap, 0.05, 1e-15);
  EXPECT_NEAR((t.point - Vec3(0.2, 0.5, 0.2)).norm(), 0.2, 1e-15);
  // Centre inside the core: out through the nearest face, the overlap counted from the
  // outer surface.
  t = touch_wall(box, Vec3(0.5, 0.75, 0.5), r);
  EXPECT_TRUE(t.normal.isApprox(Vec3::UnitY()));
  EXPECT_NEAR(t.overlap, r + 0.25, 1e-12);
  EXPECT_NEAR(t.point.y(), 1.0, 1e-15);
}

TEST(Walls, EdgeRadiusIsRefusedOnAPlaneAndWhenItSwallowsTheBox) {
  const Material m{1e6, 1e6, 0.3};
  Wall plane;
  plane.material = m;
  plane.edge_radius = 0.01;
  EXPECT_THROW(validate_wall(plane, 0), SetupError);
  Wall box;
  box.shape = WallShape::Box;
  box.material = m;
  box.hi = Vec3(1.0, 1.0, 0.1);
  box.edge_radius = 0.05;  // half the smallest side: no core left
  EXPECT_THROW(validate_wall(box, 0), SetupError);
  box.edge_radius = 0.049;
  EXPECT_NO_THROW(validate_wall(box, 0));
}

TEST(Walls, BoxContainerHasFiveInwardFacesWhenOpen) {
  const Material m{1e6, 1e6, 0.3};
  const auto walls = box_container(Vec3::Zero(), Vec3(0.7, 0.3, 0.45), m, m, true);
  ASSERT_EQ(walls.size(), 5u);
  const Vec3 inside(0.35, 0.15, 0.2);
  for (const Wall& w : walls) EXPECT_GT(w.normal.dot(inside - w.point), 0.0) << w.name;
}
