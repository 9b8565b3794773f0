// 1,000 frictional spheres falling into the box with no damping at all: every joule
// gravity releases must show up as kinetic energy, elastic energy in the contacts or
// heat from Coulomb slip. The budget must close within 1 % of the initial energy.
//
// The accounting is exact; what remains is the leapfrog's O(dt²) error on contacts
// that last only a handful of steps (a 36 mm sphere on a 2.5e9 N/m contact rings at
// ~3e5 rad/s). At dt = 0.8·dt_critical this scene drifts by ~10 % of its energy; at
// 0.15 by ~0.3 % (docs/ACCURACY.md measures the whole curve). The test runs at 0.15.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "cases/bed.hpp"

using namespace ballast;

TEST(EnergyBudget, ClosesForUndampedFrictionalSettling) {
  omp_set_num_threads(omp_get_num_procs());  // runs alone (RUN_SERIAL): use every core
  BedOptions o;
  o.count = 1000;
  o.friction = 0.5;
  o.local_damping = 0.0;
  o.damping_ratio = 0.0;
  o.rubber_base = false;
  o.gravity = Vec3(0, 0, -9.81 * 10);  // enhanced gravity: more collisions per step
  o.dt_safety = 0.15;
  Simulation sim = make_bed(o);
  sim.prepare();
  // Initial energy: potential energy above the base (the initial kinetic energy is 0).
  double e0 = 0.0;
  for (Index b = 0; b < sim.bodies().size(); ++b)
    e0 += sim.bodies().mass[b] * 9.81 * 10 *
          (sim.bodies().position[b].z() - sim.balls().radius[sim.bodies().first_ball[b]]);
  while (sim.time() < 0.15) sim.step();
  const EnergyBudget e = sim.energy();
  // The run must have done something worth checking: a real share of the energy
  // released, contacts formed and friction working.
  EXPECT_GT(e.gravity_work, 0.1 * e0);
  EXPECT_GT(e.friction_dissipated, 1e-3 * e0);
  EXPECT_GT(sim.contacts().ball_contacts, 500) << "balance " << e.balance() << " of " << e0;
  EXPECT_EQ(e.damping_dissipated, 0.0);
  EXPECT_NEAR(e.balance(), 0.0, 0.01 * e0)
      << "kinetic " << e.kinetic() << " elastic " << e.elastic << " friction "
      << e.friction_dissipated << " gravity work " << e.gravity_work;
}
