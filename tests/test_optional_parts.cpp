// A scene pays only for what it uses (docs/PERFORMANCE.md, "What a scene pays for").
// Leaving a part out must change no bit of the motion, and what is left out must
// really be gone:
//   - the energy ledger (SimulationSettings::energy_ledger): off, the bodies follow
//     the same trajectory to the bit, and energy() says the balance is unknown;
//   - the spin of frictionless spheres: their contact forces pass through the centre,
//     so no torque acts and a sphere keeps its angular velocity to the bit, on the
//     scalar pass, the general (clump-capable) path and the SIMD kernel.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cases/bed.hpp"
#include "engine/state_hash.hpp"
#include "settling_clump_bed.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

struct Motion {
  std::uint64_t motion = 0;  // motion_hash: positions, velocities, orientations, rotations
  EnergyBudget energy;
  long ball_contacts = 0;
  double booked = 0.0;  // J, Σ|entry| over every body's and ball's ledger entries
};

double sum_abs(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += std::abs(x);
  return s;
}

Motion run_bed(BedOptions o, bool ledger, double seconds) {
  test_support::ScopedThreads one(1);
  o.sim.energy_ledger = ledger;
  Simulation sim = make_bed(o);
  while (sim.time() < seconds) sim.step();
  const BodyStore& b = sim.bodies();
  return {motion_hash(b), sim.energy(), sim.contacts().ball_contacts,
          sum_abs(b.gravity_work) + sum_abs(b.damping_dissipated) +
              sum_abs(sim.balls().friction_dissipated) + sum_abs(sim.balls().viscous_dissipated)};
}

// With the ledger every loss is booked and the balance closes; without it the same
// kinetic energy, no work terms and an unknown balance, and not one entry written
// (the work is not done, not merely hidden).
void expect_ledger_only_in_the_books(const Motion& on, const Motion& off) {
  EXPECT_TRUE(on.energy.booked);
  EXPECT_GT(on.energy.gravity_work, 0.0);
  EXPECT_GT(on.energy.damping_dissipated, 0.0);
  EXPECT_LT(std::abs(on.energy.balance()), 0.05 * on.energy.gravity_work);
  EXPECT_GT(on.booked, 0.0);
  EXPECT_EQ(off.booked, 0.0);
  EXPECT_FALSE(off.energy.booked);
  EXPECT_TRUE(std::isnan(off.energy.balance()));
  EXPECT_EQ(off.energy.gravity_work, 0.0);
  EXPECT_EQ(off.energy.damping_dissipated, 0.0);
  EXPECT_EQ(off.energy.friction_dissipated, 0.0);
  EXPECT_EQ(off.energy.viscous_dissipated, 0.0);
  EXPECT_EQ(off.energy.kinetic(), on.energy.kinetic());
  EXPECT_EQ(off.energy.elastic, on.energy.elastic);
}

BedOptions frictionless_spheres(double damping_ratio) {
  BedOptions o;
  o.count = 300;
  o.length = 0.35;
  o.volume_fraction = 0.35;
  o.friction = 0.0;
  o.sim.damping_ratio = damping_ratio;
  o.sim.local_damping = 0.7;
  o.sim.gravity = Vec3(0, 0, -981.0);  // 100 g: a bed within 0.05 s
  return o;
}

}  // namespace

// A settling clump bed with every loss at work (slip, local damping, dashpots): the
// ledger is bookkeeping only. Mutations caught: the ledger-off integrator booking
// gravity's work all the same; leaving out local damping along with its work (the
// trajectories part).
TEST(OptionalParts, LedgerOffMovesNoBitOfAClumpBed) {
  BedOptions o = settling_clump_bed_options();
  const Motion on = run_bed(o, true, 0.04), off = run_bed(o, false, 0.04);
  EXPECT_GT(on.ball_contacts, o.count);  // a bed forms: contacts, slip, dashpots
  EXPECT_GT(on.energy.friction_dissipated, 0.0);
  EXPECT_GT(on.energy.viscous_dissipated, 0.0);
  EXPECT_EQ(on.motion, off.motion);
  expect_ledger_only_in_the_books(on, off);
}

// The same for spheres without dashpots: the SIMD kernel and the lane update, where
// the CPU has them (the scalar pass elsewhere).
TEST(OptionalParts, LedgerOffMovesNoBitOfASphereBed) {
  BedOptions o = frictionless_spheres(0.0);
  o.friction = 0.5;
  const Motion on = run_bed(o, true, 0.05), off = run_bed(o, false, 0.05);
  EXPECT_GT(on.ball_contacts, o.count / 2);  // a bed forms (measured 269)
  EXPECT_GT(on.energy.friction_dissipated, 0.0);
  EXPECT_EQ(on.motion, off.motion);
  expect_ledger_only_in_the_books(on, off);
}

// Frictionless spheres poured into a bed, each spun at the start: no torque acts on
// them, so every angular velocity ends as it began, to the bit, and the rotational
// kinetic energy with it, while the bed forms (hundreds of contacts, with and
// without dashpots, on the sphere path, the general path and the SIMD kernel).
// Mutation caught: the frictionless pass computing n × (Fn·n) again (its roundoff
// moves ω in the last bits).
TEST(OptionalParts, FrictionlessSpheresKeepTheirSpinExactly) {
  struct Case {
    const char* name;
    double damping_ratio;
    bool fast_path;
  };
  for (const Case c :
       {Case{"dashpots, sphere path", 0.1, true}, Case{"dashpots, general path", 0.1, false},
        Case{"no dashpots, SIMD kernel or scalar", 0.0, true}}) {
    SCOPED_TRACE(c.name);
    test_support::ScopedThreads one(1);
    BedOptions o = frictionless_spheres(c.damping_ratio);
    o.sim.sphere_fast_path = c.fast_path;
    Simulation sim = make_bed(o);
    std::vector<Vec3> spin(sim.bodies().size());
    for (Index b = 0; b < sim.bodies().size(); ++b) {
      spin[b] = Vec3(std::sin(1.0 + b), std::cos(2.0 * b), 0.5 - 0.01 * b) * 30.0;  // rad/s
      sim.set_body_angular_velocity(b, spin[b]);
    }
    const double rotational0 = sim.energy().kinetic_rotational;
    long steps = 0;
    while (sim.time() < 0.05) sim.step(), ++steps;
    EXPECT_GT(sim.contacts().ball_contacts, o.count / 2);  // measured 226-251
    for (Index b = 0; b < sim.bodies().size(); ++b) {
      ASSERT_EQ(sim.bodies().angular_velocity[b], spin[b]) << "sphere " << b;
      ASSERT_EQ(sim.bodies().torque[b], Vec3::Zero()) << "sphere " << b;
      // The accumulated rotation is Σ ω·dt with ω constant (dt is refreshed as the
      // bed forms, so the sum is compared with t·ω, to rounding).
      ASSERT_LT((sim.bodies().rotation[b] - sim.time() * spin[b]).norm(),
                1e-9 * sim.time() * spin[b].norm())
          << "sphere " << b;
    }
    EXPECT_EQ(sim.energy().kinetic_rotational, rotational0);
  }
}
