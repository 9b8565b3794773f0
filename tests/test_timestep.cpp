// Critical timestep estimate and its report.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "engine/errors.hpp"
#include "test_helpers.hpp"

using namespace ballast;

TEST(Timestep, IsolatedSphereUsesOneContactWithItsTwin) {
  const double r = 0.02, rho = 2600, k = 4e8;
  SimulationSettings s = scenes::bare_settings();
  Simulation sim(s);
  const Index mat = sim.add_material({k, k, 0.5});
  sim.add_sphere(Vec3::Zero(), r, rho, mat);
  sim.prepare();
  const double m = scenes::sphere_mass(r, rho);
  // Translation: k_tran = k/2 + k/2 = k; rotation: k_rot = (k/2)·r² with I = 0.4·m·r².
  // ω² = k/m + (k/2)/(0.4·m) = 2.25·k/m.
  const double expected = 1.0 / std::sqrt(2.25 * k / m);
  EXPECT_NEAR(sim.critical_dt(), expected, 1e-12 * expected);
  EXPECT_NEAR(sim.dt(), 0.8 * expected, 1e-12 * expected);
}

TEST(Timestep, SixContactsGiveTheSummedStiffness) {
  const double r = 0.02, rho = 2600, k = 4e8;
  SimulationSettings s = scenes::bare_settings();
  Simulation sim(s);
  const Index mat = sim.add_material({k, k, 0.5});
  sim.add_sphere(Vec3::Zero(), r, rho, mat);  // the centre ball, body 0
  for (int a = 0; a < 3; ++a)
    for (double sgn : {-1.0, 1.0})
      sim.add_sphere(sgn * (2 * r - 1e-5) * Vec3::Unit(a), r, rho, mat);
  sim.prepare();
  const double m = scenes::sphere_mass(r, rho);
  // The centre ball touches 6 others: k_tran = 6·(k/2 + k/2) = 6k and
  // k_rot = 6·(k/2)·r² (each contact's shear spring; a normal force has no lever
  // arm on a sphere), so ω² = 6k/m + 3k/(0.4·m) = 13.5·k/m.
  const double expected = 1.0 / std::sqrt(13.5 * k / m);
  EXPECT_NEAR(sim.critical_dt(), expected, 1e-9 * expected);
}

TEST(Timestep, StartReportGivesTheRatioAndWarnsWhenTooLarge) {
  std::ostringstream log;
  SimulationSettings s = scenes::bare_settings();
  s.log = &log;
  s.fixed_dt = 1e-3;  // far above critical for these stiffnesses
  Simulation sim(s);
  const Index mat = sim.add_material({1e8, 1e8, 0.0});
  sim.add_sphere(Vec3::Zero(), 0.02, 2600, mat);
  sim.prepare();
  EXPECT_NE(log.str().find("dt/dt_critical"), std::string::npos);
  EXPECT_NE(log.str().find("warning"), std::string::npos);
  EXPECT_GT(sim.dt() / sim.critical_dt(), 1.0);
}

TEST(Timestep, StrictModeRefusesADtAboveCritical) {
  SimulationSettings s = scenes::bare_settings();
  s.fixed_dt = 1e-3;
  s.strict_timestep = true;
  Simulation sim(s);
  const Index mat = sim.add_material({1e8, 1e8, 0.0});
  sim.add_sphere(Vec3::Zero(), 0.02, 2600, mat);
  EXPECT_THROW(sim.prepare(), SetupError);
}
