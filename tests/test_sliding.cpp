// A sphere launched sliding without spin on a frictional plane: friction slows it
// and spins it up until it rolls, at v = 5/7·v0 (solid sphere, I = 2/5·m·r²).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "test_helpers.hpp"

using namespace ballast;

namespace {

constexpr double kR = 0.02, kRho = 2600.0, kG = 9.81, kK = 1e7, kDt = 1e-6;

// A sphere of friction mu_ball launched at v0 along x, without spin, on a plane of
// friction mu_wall, under gravity. It starts at its static overlap, so the normal
// force is m·g from the first step.
struct SlidingSphere {
  Simulation sim;
  Index body = 0;
};

SlidingSphere sliding_sphere(double mu_ball, double mu_wall, double v0) {
  SimulationSettings s = scenes::bare_settings(0.5);
  s.gravity = Vec3(0, 0, -kG);
  s.fixed_dt = kDt;
  SlidingSphere out{Simulation(s), 0};
  const Index mat = out.sim.add_material({2 * kK, 2 * kK, mu_ball});
  out.sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), {2 * kK, 2 * kK, mu_wall}));
  const double m = scenes::sphere_mass(kR, kRho);
  out.body = out.sim.add_sphere(Vec3(-0.4, 0, kR - m * kG / kK), kR, kRho, mat);
  out.sim.set_body_velocity(out.body, Vec3(v0, 0, 0));
  return out;
}

}  // namespace

TEST(Sliding, SlipStopsAtFiveSeventhsOfLaunchSpeed) {
  const double mu = 0.3, v0 = 1.0;
  SlidingSphere p = sliding_sphere(mu, mu, v0);
  // Sliding lasts t = 2·v0/(7·mu·g) ≈ 0.097 s; run twice that.
  const double t_slide = 2 * v0 / (7 * mu * kG);
  p.sim.run(static_cast<long>(2 * t_slide / kDt));
  const double v = p.sim.bodies().velocity[p.body].x();
  EXPECT_NEAR(v, 5.0 / 7.0 * v0, 0.01 * 5.0 / 7.0 * v0);
  // Rolling without slip: ω·r = v.
  EXPECT_NEAR(p.sim.bodies().angular_velocity[p.body].y() * kR, v, 0.01 * v);
}

// The paper raises friction from 0.3 (compaction) to 0.5 (loading) mid-run. While a
// sphere slips, its deceleration is exactly mu·g, so the change shows at once.
TEST(Sliding, FrictionChangeTakesEffectMidRun) {
  const double v0 = 2.0;
  SlidingSphere p = sliding_sphere(0.3, 0.3, v0);
  p.sim.run(50000);  // 0.05 s at mu = 0.3 (slip would last 2·v0/(7·0.3·g) = 0.19 s)
  const double v1 = p.sim.bodies().velocity[p.body].x();
  EXPECT_NEAR(v1, v0 - 0.3 * kG * 0.05, 0.01 * 0.3 * kG * 0.05);
  p.sim.set_all_friction(0.5);
  p.sim.run(50000);  // 0.05 s at mu = 0.5, still slipping
  const double v2 = p.sim.bodies().velocity[p.body].x();
  EXPECT_NEAR(v1 - v2, 0.5 * kG * 0.05, 0.01 * 0.5 * kG * 0.05);
}

// Two materials: a contact slips at the smaller of the two friction coefficients
// (engine/material.hpp, contact_friction; PFC's rule). A sphere of μ 0.6 on a wall
// of μ 0.3, and one of μ 0.3 on a wall of μ 0.6, both slow at 0.3·g while slipping.
// Mutations caught: min swapped for max (0.6·g), or the wall's μ ignored (0.6·g on
// the first; tests/mutations.tsv).
TEST(Sliding, TwoMaterialsSlipAtTheSmallerFriction) {
  const double v0 = 2.0;
  for (const auto& [mu_ball, mu_wall] : {std::pair{0.6, 0.3}, std::pair{0.3, 0.6}}) {
    SlidingSphere p = sliding_sphere(mu_ball, mu_wall, v0);
    p.sim.run(50000);  // 0.05 s; at 0.3·g slip lasts 2·v0/(7·0.3·g) = 0.19 s
    const double slowed = v0 - p.sim.bodies().velocity[p.body].x();
    EXPECT_NEAR(slowed, 0.3 * kG * 0.05, 0.01 * 0.3 * kG * 0.05)
        << "ball mu " << mu_ball << " on wall mu " << mu_wall;
  }
  // Ball on ball: the pair table the force loop reads holds the same rule, every law.
  PairTable pairs;
  for (int law = 0; law < kContactLawCount; ++law) {
    pairs.build({Material{1e7, 1e7, 0.6, 5e10, 0.25}, Material{1e7, 1e7, 0.3, 5e10, 0.25}}, {},
                law);
    EXPECT_EQ(pairs.balls(0, 1).mu, 0.3) << contact_law_name(law);
    EXPECT_EQ(pairs.balls(1, 0).mu, 0.3) << contact_law_name(law);
    EXPECT_EQ(pairs.balls(0, 0).mu, 0.6) << contact_law_name(law);
  }
}

// PFC drops a contact's shear force when the contact breaks. A neighbour rebuild
// between the last step a contact touched and the first it is found open used to
// lose that: the rebuild carried the pair's shear force but marked it open, and the
// force pass clears only contacts it knew as touching, so the stale force stayed and
// came back the next time the pair touched. A sphere sliding on a plane builds ~3 N
// of shear, lifts off by 1 µm, and the list is rebuilt before the step that finds it
// open.
TEST(Sliding, ShearForceIsDroppedWhenAContactOpensAcrossARebuild) {
  const double r = 0.02, rho = 2600.0, k = 1e7, dt = 1e-6, overlap = 1e-6;
  SimulationSettings s = scenes::bare_settings(1.0);
  s.fixed_dt = dt;
  Simulation sim(s);
  const Index mat = sim.add_material({2 * k, 2 * k, 0.5});
  const Index wall =
      sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), {2 * k, 2 * k, 0.5}));
  const Index b = sim.add_sphere(Vec3(0, 0, r - overlap), r, rho, mat);
  sim.set_body_velocity(b, Vec3(0.1, 0, 0));  // k·v·dt = 1 N of shear a step, cap 5 N
  sim.run(3);
  ASSERT_EQ(sim.wall_contacts().size(), 1);
  EXPECT_GT(sim.wall_contacts().shear_force[0].norm(), 2.0);
  sim.set_body_velocity(b, Vec3(0, 0, 2.0));  // up 2 µm in the next step: 1 µm clear
  sim.run(1);
  sim.set_body_velocity(b, Vec3::Zero());
  sim.set_body_angular_velocity(b, Vec3::Zero());  // the slide had spun it up
  sim.move_wall(wall, Vec3::Zero());               // forces a rebuild at the next step
  const long builds = sim.neighbour_builds();
  sim.run(1);
  EXPECT_EQ(sim.neighbour_builds(), builds + 1);
  ASSERT_EQ(sim.wall_contacts().size(), 1);  // still a candidate, not touching
  EXPECT_FALSE(sim.wall_contacts().active[0]);
  EXPECT_EQ(sim.wall_contacts().shear_force[0].norm(), 0.0);
  sim.set_body_velocity(b, Vec3(0, 0, -2.0));  // back into contact, without sliding
  sim.run(2);                                  // moves in, then finds it touching
  EXPECT_TRUE(sim.wall_contacts().active[0]);
  EXPECT_LT(sim.wall_contacts().shear_force[0].norm(), 1e-6);  // a new contact: no old shear
}
