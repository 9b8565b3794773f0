// The Hertz–Mindlin contact law (engine/law_hertz_mindlin.hpp) against closed forms:
// Hertz's impact (duration and depth), the restitution of an undamped and of a
// damped impact, the static overlap and stored energy under a load, and Mindlin's
// tangential stiffness up to the Coulomb cap. What every law must satisfy (its
// stiffness, energy and inverse against its force; its own kernel) is
// tests/test_contact_laws.cpp's.
//
// Closed forms (Johnson, Contact Mechanics, ch. 4 and 11), for a pair of effective
// radius R*, mass m*, modulus E* approaching at v:
//   depth     δmax = (15·m*·v²/(16·E*·√R*))^(2/5)
//   duration  tc = 2.9432·δmax/v   (2·∫₀¹ dx/√(1 − x^(5/2)) = 2.9432)
//   static    δ = (3·F/(4·E*·√R*))^(2/3) under a force F, storing (2/5)·F·δ
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/contact_laws.hpp"
#include "test_helpers.hpp"

using namespace ballast;
using test_support::expect_error;

namespace {

constexpr double kR = 0.02, kRho = 2600.0, kE = 1e9, kNu = 0.25;

// E* of two equal materials, Pa.
double e_star(double e, double nu) {
  return e / (2.0 * (1.0 - nu * nu));
}

SimulationSettings hertz_settings() {
  SimulationSettings s = scenes::bare_settings();
  s.contact_law = "hertz_mindlin";
  return s;
}

Material hertz_material(double mu = 0.0) {
  Material m;
  m.mu = mu;
  m.young_modulus = kE;
  m.poisson_ratio = kNu;
  return m;
}

struct Impact {
  double duration;     // s, first to last step with overlap
  double depth;        // m, the deepest overlap
  double restitution;  // separation speed / approach speed
};

// Two spheres of radius kR approach along x at ±v0, with contact damping ratio β,
// the step 1/1000 of Hertz's duration at 0.2 m/s.
Impact collide(double v0, double damping_ratio) {
  const double m_eff = 0.5 * scenes::sphere_mass(kR, kRho), r_eff = 0.5 * kR;
  const double depth =
      std::pow(15.0 * m_eff * 0.04 / (16.0 * e_star(kE, kNu) * std::sqrt(r_eff)), 0.4);
  SimulationSettings s = hertz_settings();
  s.damping_ratio = damping_ratio;
  s.fixed_dt = 2.9432 * depth / 0.2 / 1000.0;
  Simulation sim(s);
  const Index mat = sim.add_material(hertz_material());
  const Index a = sim.add_sphere(Vec3(-kR - 1e-5, 0, 0), kR, kRho, mat);
  const Index b = sim.add_sphere(Vec3(kR + 1e-5, 0, 0), kR, kRho, mat);
  sim.set_body_velocity(a, Vec3(v0, 0, 0));
  sim.set_body_velocity(b, Vec3(-v0, 0, 0));
  double t_first = -1, t_last = -1, deepest = 0.0;
  for (int k = 0; k < 200000; ++k) {
    sim.step();
    const double gap = (sim.bodies().position[b] - sim.bodies().position[a]).norm() - 2 * kR;
    if (gap < 0) {
      if (t_first < 0) t_first = sim.time();
      t_last = sim.time();
      deepest = std::max(deepest, -gap);
    } else if (t_first >= 0) {
      break;
    }
  }
  const double v_sep = sim.bodies().velocity[b].x() - sim.bodies().velocity[a].x();
  return {t_last - t_first + s.fixed_dt.value(), deepest, v_sep / (2 * v0)};
}

}  // namespace

// Depth and duration to 1 %: the step is 1/1000 of the duration, so the discrete
// contact starts and ends within a step of the continuous one. A linear normal
// spring of any stiffness fails one of the two (its duration does not depend on
// the speed, Hertz's falls as v^(-1/5), checked at 0.1 and 1 m/s).
TEST(HertzMindlin, ImpactDepthAndDurationMatchHertz) {
  const double m_eff = 0.5 * scenes::sphere_mass(kR, kRho), r_eff = 0.5 * kR;
  for (const double v0 : {0.1, 1.0}) {
    const double v = 2 * v0;
    const double depth =
        std::pow(15.0 * m_eff * v * v / (16.0 * e_star(kE, kNu) * std::sqrt(r_eff)), 0.4);
    const Impact res = collide(v0, 0.0);
    EXPECT_NEAR(res.depth, depth, 0.01 * depth) << "v0 " << v0;
    EXPECT_NEAR(res.duration, 2.9432 * depth / v, 0.01 * 2.9432 * depth / v) << "v0 " << v0;
    EXPECT_NEAR(res.restitution, 1.0, 1e-3) << "v0 " << v0;
  }
}

// The dashpots follow the tangent stiffness (c ∝ δ^¼), which makes the restitution
// independent of the impact speed (Tsuji et al. 1992): measured 0.7073 and 0.7072 at
// 0.1 and 1 m/s for β = 0.1, 0.3350 and 0.3348 for β = 0.3. With the normal dashpot
// on a fixed stiffness (the tangent one at the slow impact's depth) instead, e went
// from 0.62 to 0.75 (β = 0.1) and from 0.17 to 0.38 (β = 0.3): the test failed.
TEST(HertzMindlin, DampedRestitutionDoesNotDependOnTheImpactSpeed) {
  for (const double beta : {0.1, 0.3}) {
    const double slow = collide(0.1, beta).restitution, fast = collide(1.0, beta).restitution;
    EXPECT_LT(slow, 0.95) << "beta " << beta;  // the dashpot acts
    EXPECT_GT(slow, 0.2) << "beta " << beta;
    EXPECT_NEAR(fast, slow, 0.01 * slow) << "beta " << beta;
  }
}

// A sphere resting on a plane under gravity: δ = (3mg/(4E*√R))^(2/3), storing
// (2/5)·mg·δ, to 0.1 % once local damping has brought it to rest. The wall is the
// same material, so E* = E/(2(1 − ν²)) and R* is the ball's radius.
TEST(HertzMindlin, StaticOverlapAndStoredEnergyUnderItsWeight) {
  SimulationSettings s = hertz_settings();
  s.local_damping = 0.7;
  s.gravity = Vec3(0, 0, -9.81);
  Simulation sim(s);
  const Index mat = sim.add_material(hertz_material());
  sim.add_wall(scenes::plane_wall(Vec3(0, 0, -0.5), Vec3::UnitZ(), hertz_material()));
  const Index ball = sim.add_sphere(Vec3(0, 0, -0.5 + kR), kR, kRho, mat);
  while (sim.time() < 0.2) sim.step();
  const double weight = scenes::sphere_mass(kR, kRho) * 9.81;
  const double overlap = std::cbrt(std::pow(3.0 * weight / (4.0 * e_star(kE, kNu)), 2) / kR);
  const double measured = -0.5 + kR - sim.bodies().position[ball].z();
  EXPECT_NEAR(measured, overlap, 1e-3 * overlap);
  EXPECT_NEAR(sim.energy().elastic, 0.4 * weight * overlap, 1e-3 * 0.4 * weight * overlap);
  EXPECT_NEAR(sim.wall_contacts().normal_force[0], weight, 1e-3 * weight);
}

// Mindlin's no-slip spring at a fixed overlap: the shear force grows by kt·v·dt a
// step, kt = 8·G*·√(R*·δ), until it reaches mu·Fn, where it stays; the stored
// energy is (2/5)·Fn·δ + Fs²/(2kt) on the way.
TEST(HertzMindlin, TangentialStiffnessIsMindlinsUpToTheCoulombCap) {
  const Material m = hertz_material(0.5);
  const PairProperties p = HertzMindlinLaw::mix(m, m);
  const double g = kE / (2.0 * (1.0 + kNu)), g_star = g / (2.0 * (2.0 - kNu));
  ContactState c{};
  c.overlap = 1e-5;
  c.normal = {0.0, 0.0, 1.0};
  c.vrel = {1e-3, 0.0, 0.0};
  c.radius = 0.5 * kR;
  c.dt = 1e-6;
  const double a = std::sqrt(c.radius * c.overlap);
  const double fn = 4.0 / 3.0 * e_star(kE, kNu) * a * c.overlap, kt = 8.0 * g_star * a;
  V3 shear{0.0, 0.0, 0.0};
  for (int step = 1; step <= 10; ++step) {
    const ContactResult r = HertzMindlinLaw::force<true, false>(c, p, shear);
    const double expected = kt * 1e-3 * 1e-6 * step;  // opposes the relative slip
    EXPECT_NEAR(r.normal_force, fn, 1e-12 * fn);
    EXPECT_NEAR(shear.x, -expected, 1e-12 * expected) << "step " << step;
    const double energy =
        HertzMindlinLaw::elastic_energy(p, c.radius, r.normal_force, dot(shear, shear));
    const double stored = 0.4 * fn * c.overlap + expected * expected / (2.0 * kt);
    EXPECT_NEAR(energy, stored, 1e-9 * stored) << "step " << step;
  }
  c.vrel = {100.0, 0.0, 0.0};  // far past the cap in one step
  const ContactResult r = HertzMindlinLaw::force<true, false>(c, p, shear);
  EXPECT_NEAR(shear.x, -0.5 * fn, 1e-12 * fn);
  EXPECT_GT(r.slip_work, 0.0);
}

// A law's parameters are checked where a material enters the scene, by the law's
// own ranges, and named.
TEST(HertzMindlin, OutOfRangeModuliAreRefusedByName) {
  Simulation sim(hertz_settings());
  Material m = hertz_material();
  m.poisson_ratio = 0.5;
  expect_error([&] { sim.add_material(m); }, {"poisson_ratio", "0.5", "[0, 0.5)"});
  m = hertz_material();
  m.young_modulus = 0.0;
  expect_error([&] { sim.add_material(m); }, {"young_modulus", "> 0 Pa"});
  // The linear law's stiffnesses mean nothing to this law: a material without them
  // is valid here.
  EXPECT_NO_THROW(sim.add_material(hertz_material()));
}
