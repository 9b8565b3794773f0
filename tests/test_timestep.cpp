// Critical timestep estimate and its report.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <sstream>
#include <string>

#include "engine/contact_laws.hpp"
#include "engine/errors.hpp"
#include "engine/timestep.hpp"
#include "settling_clump_bed.hpp"
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
  // The numbers the report prints (six significant digits) are the run's.
  const std::string text = log.str();
  const auto number_after = [&](const std::string& label) {
    const std::size_t at = text.find(label);
    EXPECT_NE(at, std::string::npos) << "no '" << label << "' in: " << text;
    return at == std::string::npos ? -1.0 : std::stod(text.substr(at + label.size()));
  };
  EXPECT_NEAR(number_after("dt = "), sim.dt(), 1e-5 * sim.dt());
  EXPECT_NEAR(number_after("critical = "), sim.critical_dt(), 1e-5 * sim.critical_dt());
  const double ratio = sim.dt() / sim.critical_dt();
  EXPECT_GT(ratio, 1.0);
  EXPECT_NEAR(number_after("dt/dt_critical = "), ratio, 1e-5 * ratio);
  EXPECT_NE(text.find("warning"), std::string::npos) << text;
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

namespace {

TimestepEstimate estimate_on(const Simulation& sim, int threads) {
  test_support::ScopedThreads team(threads);
  return estimate_critical_timestep(sim.balls(), sim.bodies(), sim.materials(), sim.walls(),
                                    sim.ball_contacts(), sim.wall_contacts(), 0.1,
                                    contact_law_index(sim.settings().contact_law),
                                    sim.settings().max_speed);
}

}  // namespace

// The estimate runs on the step's threads; each takes a range of bodies and the
// ranges are combined in order, so it must be the serial loop's to the bit, body
// and mode included, on any team (three threads: ranges of unequal length).
TEST(Timestep, EstimateIsTheSameOnOneTwoAndThreeThreads) {
  test_support::ScopedThreads serial(1);
  Simulation sim = make_bed(settling_clump_bed_options());
  while (sim.time() < 0.05) sim.step();  // fallen: in contact with each other and the walls
  ASSERT_GT(sim.contacts().ball_contacts, 20);
  const TimestepEstimate one = estimate_on(sim, 1);
  ASSERT_TRUE(std::isfinite(one.critical));
  ASSERT_NE(one.limiting_body, kNoIndex);
  for (int threads : {2, 3}) {
    const TimestepEstimate many = estimate_on(sim, threads);
    EXPECT_EQ(many.critical, one.critical) << threads << " threads";
    EXPECT_EQ(many.limiting_body, one.limiting_body) << threads << " threads";
    EXPECT_EQ(many.limited_by_rotation, one.limited_by_rotation) << threads << " threads";
  }
}

// Equal spheres apart from each other have equal estimates: the first body limits,
// as in the serial loop, whichever thread's range holds the others.
TEST(Timestep, ATieGoesToTheFirstBodyOnAnyTeam) {
  SimulationSettings s = scenes::bare_settings();
  Simulation sim(s);
  const Index mat = sim.add_material({4e8, 4e8, 0.5});
  for (int k = 0; k < 7; ++k) sim.add_sphere(Vec3(0.1 * k, 0, 0), 0.02, 2600, mat);
  sim.prepare();
  for (int threads : {1, 2, 3}) EXPECT_EQ(estimate_on(sim, threads).limiting_body, 0);
}
