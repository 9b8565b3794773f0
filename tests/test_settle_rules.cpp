// The stopping rules of the box test's settling stages (cases/box_test_prepare.hpp):
// the seating of the sleeper ends at equilibrium or once the bed creeps at a steady
// rate, never while the creep is still slowing down or the bed is not quasi-static.
// The sleeper's depth is a function of time here, so each rule sees exactly the creep
// history it is meant to judge.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "cases/box_test_prepare.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

constexpr double kR = 0.01, kRho = 2600.0, kG = 9.81, kK = 1e6;

// Two spheres stacked on a floor, placed at their static overlaps (series stiffness
// kK/2 everywhere): quasi-static from the first step, force ratio near zero.
Simulation stack_at_rest() {
  SimulationSettings s = scenes::bare_settings();
  s.gravity = Vec3(0, 0, -kG);
  s.local_damping = 0.7;
  Simulation sim(s);
  const Material m{kK, kK, 0.5};
  const Index mat = sim.add_material(m);
  sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), m));
  const double w = scenes::sphere_mass(kR, kRho) * kG, k = 0.5 * kK;
  const double low = kR - 2.0 * w / k, high = low + 2.0 * kR - w / k;
  sim.add_sphere(Vec3(0, 0, low), kR, kRho, mat);
  sim.add_sphere(Vec3(0, 0, high), kR, kRho, mat);
  sim.prepare();
  return sim;
}

long window_steps(const Simulation& sim) {
  return std::max(2000L, std::lround(kSettleWindow / sim.dt()));
}

}  // namespace

TEST(SettleRules, SteadyCreepEndsTheSeatingAfterTwoWindows) {
  Simulation sim = stack_at_rest();
  const long w = window_steps(sim);
  // Ratio 0: the equilibrium rule can never hold, only the creep rule can end it.
  const StageReport r = settle(sim, "preload", 0.0, 20 * w, nullptr, SettleRule::kSeated,
                               [&sim] { return 1e-3 * sim.time(); });
  EXPECT_EQ(r.ended_by, "steady creep");
  EXPECT_TRUE(r.settled());
  EXPECT_EQ(r.steps, 2 * w);
}

TEST(SettleRules, CreepThatStillSlowsDownRunsToTheStepLimit) {
  Simulation sim = stack_at_rest();
  const long w = window_steps(sim);
  // Settlement 1 − exp(−t/τ): each window creeps exp(−window/τ) of the one before,
  // 0.82 for τ = 0.05 s against the rule's 0.9.
  const double window = w * sim.dt(), tau = window / 0.2;
  const StageReport r = settle(sim, "preload", 0.0, 8 * w, nullptr, SettleRule::kSeated,
                               [&sim, tau] { return 1.0 - std::exp(-sim.time() / tau); });
  EXPECT_EQ(r.ended_by, "step limit");
  EXPECT_FALSE(r.settled());
  EXPECT_EQ(r.steps, 8 * w);
}

TEST(SettleRules, ABedThatIsNotQuasiStaticIsNotSeated) {
  // Two overlapping spheres without gravity push each other apart (force ratio 1
  // while they touch, no contacts after): a steady creep must not end the stage.
  Simulation sim(scenes::bare_settings());
  const Index mat = sim.add_material(Material{kK, kK, 0.5});
  sim.add_sphere(Vec3(0, 0, 0), kR, kRho, mat);
  sim.add_sphere(Vec3(0, 0, 2.0 * kR - 1e-4), kR, kRho, mat);
  sim.prepare();
  const long w = window_steps(sim);
  const StageReport r = settle(sim, "preload", 0.0, 6 * w, nullptr, SettleRule::kSeated,
                               [&sim] { return 1e-3 * sim.time(); });
  EXPECT_EQ(r.ended_by, "step limit");
}

TEST(SettleRules, EquilibriumEndsTheSeatingBeforeAnyCreepIsJudged) {
  Simulation sim = stack_at_rest();
  const StageReport r = settle(sim, "preload", 0.005, 400000, nullptr, SettleRule::kSeated,
                               [&sim] { return 1e-3 * sim.time(); });
  EXPECT_EQ(r.ended_by, "equilibrium");
  EXPECT_EQ(r.steps, 2000);  // the first check of the ratio
  EXPECT_LT(r.unbalanced, 0.005);
}

TEST(SettleRules, EveryRuleNamesWhatEndedTheStage) {
  Simulation sim = stack_at_rest();
  const StageReport ratio = settle(sim, "1 g", 0.005, 400000, nullptr);
  EXPECT_EQ(ratio.ended_by, "equilibrium");
  const StageReport kinetic = settle(sim, "settle", 0.005, 400000, nullptr, SettleRule::kKinetic);
  EXPECT_EQ(kinetic.ended_by, "at rest");
  Simulation falling(scenes::bare_settings());
  falling.add_material(Material{kK, kK, 0.5});
  falling.add_sphere(Vec3::Zero(), kR, kRho, 0);
  const StageReport limit = settle(falling, "compact", 0.005, 3000, nullptr);
  EXPECT_EQ(limit.ended_by, "step limit");
  EXPECT_FALSE(limit.settled());
}

TEST(SettleRules, SeatingWithoutASleeperDepthIsRefused) {
  Simulation sim = stack_at_rest();
  EXPECT_THROW(settle(sim, "preload", 0.005, 1000, nullptr, SettleRule::kSeated),
               std::invalid_argument);
}
