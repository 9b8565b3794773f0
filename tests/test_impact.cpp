// Head-on impact of two equal spheres: closed-form contact duration and restitution
// of a linear spring (with and without a dashpot).
#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.hpp"

using namespace ballast;

namespace {

struct ImpactResult {
  double duration;     // s, first to last step with overlap
  double restitution;  // separation speed / approach speed
};

// Two spheres of radius r approach along x at ±v0, with contact damping ratio β.
ImpactResult collide(double damping_ratio, double dt_fraction) {
  const double r = 0.02, rho = 2600.0, k_ball = 2.0e6, v0 = 0.1;
  SimulationSettings s = scenes::bare_settings();
  s.damping_ratio = damping_ratio;
  const double m = scenes::sphere_mass(r, rho);
  const double k = 0.5 * k_ball;  // two equal springs in series
  const double period = kPi * std::sqrt(0.5 * m / k);
  s.fixed_dt = period * dt_fraction;
  Simulation sim(s);
  const Index mat = sim.add_material({k_ball, k_ball, 0.0});
  const Index a = sim.add_sphere(Vec3(-r - 1e-4, 0, 0), r, rho, mat);
  const Index b = sim.add_sphere(Vec3(r + 1e-4, 0, 0), r, rho, mat);
  sim.set_body_velocity(a, Vec3(v0, 0, 0));
  sim.set_body_velocity(b, Vec3(-v0, 0, 0));
  double t_first = -1, t_last = -1;
  for (int k = 0; k < 200000; ++k) {
    sim.step();
    const double gap = (sim.bodies().position[b] - sim.bodies().position[a]).norm() - 2 * r;
    // Positions at the end of the step are at time t; the force acting during the
    // next step comes from them.
    if (gap < 0) {
      if (t_first < 0) t_first = sim.time();
      t_last = sim.time();
    } else if (t_first >= 0) {
      break;
    }
  }
  const double v_sep = sim.bodies().velocity[b].x() - sim.bodies().velocity[a].x();
  return {t_last - t_first + s.fixed_dt.value(), v_sep / (2 * v0)};
}

}  // namespace

TEST(Impact, UndampedDurationIsHalfPeriodOfTheContactSpring) {
  const double r = 0.02, rho = 2600.0, k = 1.0e6;
  const double m_eff = 0.5 * scenes::sphere_mass(r, rho);
  const double expected = kPi * std::sqrt(m_eff / k);
  const ImpactResult res = collide(0.0, 1.0 / 500.0);
  EXPECT_NEAR(res.duration, expected, 0.01 * expected);
}

TEST(Impact, UndampedRestitutionIsOne) {
  const ImpactResult res = collide(0.0, 1.0 / 500.0);
  EXPECT_NEAR(res.restitution, 1.0, 1e-3);
}

TEST(Impact, ViscousRestitutionMatchesDampingRatio) {
  for (double beta : {0.05, 0.2, 0.5}) {
    const double expected = std::exp(-kPi * beta / std::sqrt(1 - beta * beta));
    const ImpactResult res = collide(beta, 1.0 / 1000.0);
    EXPECT_NEAR(res.restitution, expected, 0.01 * expected) << "beta = " << beta;
  }
}
