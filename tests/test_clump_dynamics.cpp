// Clumps in the engine: they must really rotate (LAMMPS once let granular rigid
// bodies sit still), conserve angular momentum when nothing external acts, and come
// to rest on a floor like a body, not like a set of balls.
#include <gtest/gtest.h>

#include <cmath>

#include "cases/clump_presets.hpp"
#include "engine/clump_batch.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

// Two equal balls of radius r at ±d along x: principal moments about the centre.
struct Dumbbell {
  double r = 0.01, d = 0.012, rho = 2600;
  std::vector<Vec3> offsets{Vec3(-0.012, 0, 0), Vec3(0.012, 0, 0)};
  std::vector<double> radii{0.01, 0.01};
  double mass() const { return 2 * scenes::sphere_mass(r, rho); }
  Vec3 inertia() const {
    const double m1 = scenes::sphere_mass(r, rho), i0 = 0.4 * m1 * r * r;
    return Vec3(2 * i0, 2 * (i0 + m1 * d * d), 2 * (i0 + m1 * d * d));
  }
};

Vec3 angular_momentum(const Simulation& sim) {
  const BodyStore& b = sim.bodies();
  Vec3 l = Vec3::Zero();
  for (Index k = 0; k < b.size(); ++k) {
    const Mat3 rot = b.orientation[k].toRotationMatrix();
    const Mat3 inertia = rot * b.inertia[k].asDiagonal() * rot.transpose();
    l += b.mass[k] * b.position[k].cross(b.velocity[k]) + inertia * b.angular_velocity[k];
  }
  return l;
}

}  // namespace

TEST(ClumpDynamics, FreeSpinAboutAPrincipalAxisTurnsTheBallsAtOmega) {
  Simulation sim(scenes::bare_settings());
  const Index mat = sim.add_material({1e7, 1e7, 0.0});
  Dumbbell db;
  const Index c = sim.add_clump(Vec3::Zero(), Quat::Identity(), db.offsets, db.radii, db.mass(),
                                db.inertia(), mat);
  const double omega = 3.0;  // rad/s about z
  sim.set_body_angular_velocity(c, Vec3(0, 0, omega));
  sim.prepare();
  const long steps = 10000;
  sim.run(steps);
  const double angle = omega * sim.time();
  const Vec3 expected = db.d * Vec3(std::cos(angle), std::sin(angle), 0);
  const Vec3 ball = sim.balls().position[sim.bodies().first_ball[c] + 1];
  EXPECT_NEAR((ball - expected).norm(), 0.0, 1e-9 * db.d);
  EXPECT_NEAR(sim.bodies().rotation[c].z(), angle, 1e-12 * angle);
  EXPECT_NEAR(sim.energy().kinetic_rotational, 0.5 * db.inertia().z() * omega * omega, 1e-12);
}

// The engine integrates clumps as PFC3D 3.x and the paper (eq 17) do: principal
// frame, gyroscopic term [W] dropped. Angular momentum is then conserved exactly
// while the spin stays on a principal axis, which a frictionless impact in the
// plane of the dumbbell guarantees.
TEST(ClumpDynamics, OffCentreImpactSpinsTheClumpAndConservesAngularMomentum) {
  SimulationSettings s = scenes::bare_settings();
  s.dt_safety = 0.2;
  Simulation sim(s);
  const Index mat = sim.add_material({1e7, 1e7, 0.0});
  Dumbbell db;
  const Index c = sim.add_clump(Vec3::Zero(), Quat::Identity(), db.offsets, db.radii, db.mass(),
                                db.inertia(), mat);
  // A sphere flying along -y hits the +x ball of the dumbbell: a torque about z.
  const Index ball = sim.add_sphere(Vec3(0.0125, 0.05, 0.0), 0.008, 2600, mat);
  sim.set_body_velocity(ball, Vec3(0.05, -1.0, 0.0));
  const Vec3 l0 = angular_momentum(sim);
  const double scale = sim.bodies().mass[ball] * 1.0 * 0.05;
  sim.prepare();
  while (sim.time() < 0.08) sim.step();
  EXPECT_LT(sim.bodies().angular_velocity[c].z(), -1.0);  // clockwise seen from +z
  EXPECT_NEAR((angular_momentum(sim) - l0).norm(), 0.0, 1e-9 * scale);
  EXPECT_EQ(sim.contacts().ball_contacts, 0);  // they have separated again
}

TEST(ClumpDynamics, GeneratedClumpComesToRestOnAFloor) {
  ClumpMassOptions mass;
  mass.mode = MassMode::kUniform;
  mass.accuracy = 0.005;
  const ClumpParams params = load_clump_preset("table2/sample1").params;
  const ClumpTemplate t = generate_clump_templates(params, mass, 1, 3).front();
  SimulationSettings s = scenes::bare_settings();
  s.gravity = Vec3(0, 0, -9.81);
  s.local_damping = 0.7;
  Simulation sim(s);
  const Index mat = sim.add_material({5.08e9, 5.08e9, 0.5});
  sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), {5.08e9, 5.08e9, 0.5}));
  const Quat tilted(Eigen::AngleAxisd(0.7, Vec3(1, 2, 0).normalized()));
  const Index c = sim.add_clump(Vec3(0, 0, 0.05), tilted, t, mat);
  ASSERT_GT(sim.bodies().ball_count[c], 1);
  sim.prepare();
  while (sim.time() < 2.0) sim.step();
  // At rest on at least three balls, having turned to get there.
  EXPECT_LT(sim.bodies().velocity[c].norm(), 1e-4);
  EXPECT_LT(sim.bodies().angular_velocity[c].norm(), 1e-2);
  EXPECT_GE(sim.contacts().wall_contacts, 3);
  EXPECT_GT(sim.bodies().rotation[c].norm(), 0.01);
  EXPECT_LT(sim.unbalanced_force_ratio(), 1e-2);
}
