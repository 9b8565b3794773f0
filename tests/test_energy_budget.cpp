// The energy budget with every loss and every source (engine/diagnostics.hpp):
//   kinetic + elastic + friction + local damping + dashpots − gravity work − wall work
// stays at its initial value. Each test takes its tolerance relative to the energy
// the run puts in or releases, not to a total it never touches, and names the
// one-line mutations it catches (tests/mutations.tsv; tests/check_mutations.py).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "cases/bed.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

// `count` undamped spheres of 36.25 mm, friction 0.5, poured at 10 g into the box for
// 0.05 s (the scene of docs/ACCURACY.md; about 54 J released for 300). Returns the
// budget at the end.
EnergyBudget pour(int count, double dt_safety, double local_damping, double damping_ratio) {
  BedOptions o;
  o.count = count;
  o.friction = 0.5;
  o.sim.local_damping = local_damping;
  o.sim.damping_ratio = damping_ratio;
  o.rubber_base = false;
  o.sim.gravity = Vec3(0, 0, -98.1);
  o.sim.dt_safety = dt_safety;
  Simulation sim = make_bed(o);
  while (sim.time() < 0.05) sim.step();
  return sim.energy();
}

}  // namespace

// Leapfrog's error on a contact falls as dt², and the accounting adds none of its
// own: halving dt must cut the undamped drift (|balance| over the energy released)
// by about 4. Measured: 3.27 % at 0.4·dt_critical, 0.94 % at 0.2 (ratio 3.5).
// Mutation caught: positions advanced with the old velocity (explicit Euler, first
// order: the ratio falls to about 2 and the drift grows tenfold).
TEST(EnergyBudget, UndampedDriftFallsAsTheSquareOfTheTimestep) {
  const EnergyBudget coarse = pour(300, 0.4, 0.0, 0.0);
  const EnergyBudget fine = pour(300, 0.2, 0.0, 0.0);
  const double drift_coarse = std::abs(coarse.balance()) / coarse.gravity_work;
  const double drift_fine = std::abs(fine.balance()) / fine.gravity_work;
  std::printf(
      "undamped drift: %.3g %% at 0.4, %.3g %% at 0.2 (ratio %.2f); released %.4g J, "
      "friction %.4g J\n",
      100 * drift_coarse, 100 * drift_fine, drift_coarse / drift_fine, fine.gravity_work,
      fine.friction_dissipated);
  // The run did something worth checking: energy released and much of it taken by
  // slip (measured 56 J and 42 J: without damping the bed is still a bouncing gas).
  EXPECT_GT(fine.gravity_work, 30.0);
  EXPECT_GT(fine.friction_dissipated, 0.3 * fine.gravity_work);
  EXPECT_EQ(fine.damping_dissipated, 0.0);
  EXPECT_EQ(fine.viscous_dissipated, 0.0);
  EXPECT_LT(drift_fine, 0.015);
  EXPECT_GT(drift_coarse / drift_fine, 3.0);
  EXPECT_LT(drift_coarse / drift_fine, 5.0);
}

// The same pour with PFC's local damping and contact dashpots on: what gravity
// releases is what the bed holds plus what the three losses took.
// Mutations caught: local damping's loss booked with the wrong sign, or slip's.
TEST(EnergyBudget, DampedPourClosesWithEveryLoss) {
  const EnergyBudget e = pour(300, 0.2, 0.7, 0.1);
  std::printf(
      "damped pour: released %.4g J, damping %.4g, viscous %.4g, friction %.4g, "
      "balance %.3g J\n",
      e.gravity_work, e.damping_dissipated, e.viscous_dissipated, e.friction_dissipated,
      e.balance());
  EXPECT_GT(e.damping_dissipated, 0.1 * e.gravity_work);
  EXPECT_GT(e.viscous_dissipated, 1e-3 * e.gravity_work);
  EXPECT_GT(e.friction_dissipated, 1e-3 * e.gravity_work);
  EXPECT_NEAR(e.balance(), 0.0, 0.005 * e.gravity_work);
}

// PFC's local damping on a sphere bouncing off a wall (no gravity): on the way in
// the damping adds α·|F| to the spring's force, on the way out it takes α·|F| away,
// so the sphere leaves with e² = (1 − α)/(1 + α) of its kinetic energy and the
// ledger holds the rest. Exact but for the one step in which the velocity changes
// sign (dt = T/2000: measured errors below 1e-6). Eight spheres side by side, so
// that the SIMD update (sphere_update_lanes.hpp) takes them, and again the scalar one.
// Mutations caught: the damping's sign flipped (e > 1) in either path, its loss not
// booked.
TEST(EnergyBudget, LocalDampingTakesItsClosedFormShareOfABounce) {
  const double r = 0.02, rho = 2600.0, k = 1e6, v0 = 0.2;
  const int n = 8;
  for (int lanes : {-1, 0})
    for (double alpha : {0.1, 0.7}) {
      SimulationSettings s = scenes::bare_settings(0.5);
      s.local_damping = alpha;
      s.simd_lanes = lanes;
      const double m = scenes::sphere_mass(r, rho);
      s.fixed_dt = kPi * std::sqrt(m / k) / 2000.0;  // the contact spring is k (wall stiff)
      Simulation sim(s);
      const Index mat = sim.add_material({k, k, 0.0});
      sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), {1e15, 1e15, 0.0}));
      for (int b = 0; b < n; ++b) {
        sim.add_sphere(Vec3(-0.4 + 0.1 * b, 0, r + 1e-4), r, rho, mat);
        sim.set_body_velocity(b, Vec3(0, 0, -v0));
      }
      const double ke0 = n * 0.5 * m * v0 * v0;
      for (int step = 0; step < 20000 && !(sim.bodies().position[0].z() > r + 1e-4); ++step)
        sim.step();
      const double e_exact = std::sqrt((1 - alpha) / (1 + alpha));
      for (int b = 0; b < n; ++b)
        EXPECT_NEAR(sim.bodies().velocity[b].z() / v0, e_exact, 1e-6)
            << "alpha " << alpha << ", lanes " << lanes << ", sphere " << b;
      const EnergyBudget budget = sim.energy();
      EXPECT_NEAR(budget.damping_dissipated, ke0 * (1 - e_exact * e_exact), 1e-6 * ke0);
      // The leapfrog's O(dt²) on the spring alone remains: measured 2.6e-7.
      EXPECT_NEAR(budget.balance(), ke0, 1e-6 * ke0);
    }
}

// A bed of 64 frictional spheres under a servo lid driven 300 → 3,000 N and back at
// 20 Hz, with gravity, local damping and dashpots: the lid's work goes in and out
// of the bed, and the budget must close against it.
// Mutation caught: the wall's work booked with the wrong sign (off by twice it).
TEST(EnergyBudget, BedUnderAServoLidClosesAgainstTheLidsWork) {
  const double r = 0.02, rho = 2600.0, spacing = 2.1 * r, side = 4 * spacing;
  SimulationSettings s;
  s.domain_lo = Vec3(-0.05, -0.05, -0.05);
  s.domain_hi = Vec3(side + 0.05, side + 0.05, side + 0.1);
  s.gravity = Vec3(0, 0, -9.81);
  s.local_damping = 0.7;
  s.damping_ratio = 0.05;
  s.dt_safety = 0.2;
  Simulation sim(s);
  const Material m{1e7, 1e7, 0.3};
  const Index mat = sim.add_material(m);
  for (const Wall& w : box_container(Vec3::Zero(), Vec3(side, side, side + 0.05), m, m, true))
    sim.add_wall(w);
  const Index lid = sim.add_wall(scenes::plane_wall(Vec3(0, 0, side + 0.005), -Vec3::UnitZ(), m));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.04 * r, 0.04 * r);  // no overlap at the start
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int kz = 0; kz < 4; ++kz)
        sim.add_sphere(Vec3((i + 0.5) * spacing + jitter(rng), (j + 0.5) * spacing + jitter(rng),
                            (kz + 0.5) * spacing),
                       r, rho, mat);
  Servo servo;
  servo.walls = {lid};
  servo.target_force = sinusoidal_load(300.0, 3000.0, 20.0, 0.02);
  servo.max_speed = 0.2;
  sim.add_servo(servo);
  while (sim.time() < 0.02 + 0.1) sim.step();  // landing, then two load cycles
  const EnergyBudget e = sim.energy();
  std::printf(
      "servo lid: wall work %.4g J, gravity %.4g, damping %.4g, viscous %.4g, "
      "friction %.4g, elastic %.4g, balance %.3g J\n",
      e.wall_work, e.gravity_work, e.damping_dissipated, e.viscous_dissipated,
      e.friction_dissipated, e.elastic, e.balance());
  EXPECT_GT(e.wall_work, 0.0);
  EXPECT_GT(e.friction_dissipated, 0.0);
  EXPECT_GT(e.viscous_dissipated, 0.0);
  EXPECT_NEAR(sim.servos()[0].measured_force, sim.servos()[0].target_now, 0.05 * 3000.0);
  // Measured 5.5e-4 J of 0.92 J put in (0.06 %).
  EXPECT_NEAR(e.balance(), 0.0, 0.005 * (e.wall_work + e.gravity_work));
}

// A wall pushed at constant speed into a sphere too heavy to move (3e10 kg) loads a
// fixed spring: the wall's work must equal the spring's energy ½·K·δ² to round-off.
// Booked with the force before each move alone (a left Riemann sum), it would miss
// ½·K·Δx² a step: 1/N of the energy after N steps, 1 % here.
// Mutation caught: the trapezoid's second force left out (tests/mutations.tsv).
TEST(EnergyBudget, WallWorkOnAFixedSpringIsItsElasticEnergy) {
  const double r = 0.02, k = 1e8;
  SimulationSettings s = scenes::bare_settings(0.1);
  s.fixed_dt = 1e-5;
  Simulation sim(s);
  const Index mat = sim.add_material({k, k, 0.0});
  sim.add_sphere(Vec3::Zero(), r, 1e15, mat);
  const Index lid = sim.add_wall(
      scenes::plane_wall(Vec3(0, 0, r), -Vec3::UnitZ(), {k, k, 0.0}));  // just touching
  sim.set_wall_velocity(lid, Vec3(0, 0, -1e-3));                        // 10 nm a step
  sim.run(100);
  const EnergyBudget e = sim.energy();
  const double series = 0.5 * k, overlap = 100 * 1e-3 * 1e-5;  // 1 µm after 100 moves
  // energy() reports the contacts as of the last force pass, before the last move:
  // 99 moves in, and the work of the 100th is booked at the next step.
  const double booked = 0.5 * series * (0.99 * overlap) * (0.99 * overlap);
  EXPECT_NEAR(e.elastic, booked, 1e-9 * booked);
  EXPECT_NEAR(e.wall_work, booked, 1e-9 * booked);
  EXPECT_NEAR(e.balance(), 0.0, 1e-9 * booked);
}
