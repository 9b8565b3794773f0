// Bad set-up is refused with a message naming the field, the value and what is
// allowed; a run that blows up stops with the step, the body and the quantity.
#include <gtest/gtest.h>

#include "engine/errors.hpp"
#include "test_helpers.hpp"

using namespace ballast;

using ballast::test_support::expect_error;

TEST(SetupErrors, NegativeStiffness) {
  Simulation sim(scenes::bare_settings());
  expect_error([&] { sim.add_material({-5.0, 1e6, 0.3}); }, {"kn", "-5", "> 0"});
}

TEST(SetupErrors, BallOutsideTheDomain) {
  Simulation sim(scenes::bare_settings(1.0));
  const Index mat = sim.add_material({1e6, 1e6, 0.3});
  expect_error([&] { sim.add_sphere(Vec3(0, 0, 3.0), 0.01, 2600, mat); },
               {"ball position", "(0, 0, 3)", "inside the domain"});
}

TEST(SetupErrors, NonPositiveTimestep) {
  for (double dt : {0.0, -1e-6}) {
    SimulationSettings s = scenes::bare_settings();
    s.fixed_dt = dt;
    Simulation sim(s);
    const Index mat = sim.add_material({1e6, 1e6, 0.3});
    sim.add_sphere(Vec3::Zero(), 0.01, 2600, mat);
    expect_error([&] { sim.prepare(); }, {"dt", "> 0 s"});
  }
}

TEST(SetupErrors, RadiusDensityMaterialAndWalls) {
  Simulation sim(scenes::bare_settings());
  const Index mat = sim.add_material({1e6, 1e6, 0.3});
  expect_error([&] { sim.add_sphere(Vec3::Zero(), 0.0, 2600, mat); }, {"radius", "> 0"});
  expect_error([&] { sim.add_sphere(Vec3::Zero(), 0.01, -1, mat); }, {"density"});
  expect_error([&] { sim.add_sphere(Vec3::Zero(), 0.01, 2600, 7); }, {"material", "7"});
  Wall w = scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), {1e6, 1e6, 0.3});
  w.normal = Vec3(0, 0, 2);
  expect_error([&] { sim.add_wall(w); }, {"normal", "unit"});
  expect_error([&] { sim.set_all_friction(-0.1); }, {"mu", "-0.1"});
  expect_error([] { Simulation bad(scenes::bare_settings(-1.0)); }, {"domain"});
}

TEST(SetupErrors, UnknownContactModelListsTheRegisteredOnes) {
  SimulationSettings s = scenes::bare_settings();
  s.contact_law = "hertz";
  Simulation sim(s);
  const Index mat = sim.add_material({1e6, 1e6, 0.3});
  sim.add_sphere(Vec3::Zero(), 0.01, 2600, mat);
  expect_error([&] { sim.prepare(); }, {"contact_law", "'hertz'", "linear, hertz_mindlin"});
}

TEST(SetupErrors, BlowUpNamesStepBodyAndQuantityAndKeepsTheState) {
  SimulationSettings s = scenes::bare_settings();
  s.fixed_dt = 1e-2;  // hundreds of times the critical step
  Simulation sim(s);
  const Index mat = sim.add_material({1e9, 1e9, 0.0});
  sim.add_sphere(Vec3(-0.0199, 0, 0), 0.01, 2600, mat);
  sim.add_sphere(Vec3(0.0, 0, 0), 0.01, 2600, mat);
  try {
    sim.run(1000);
    FAIL() << "the run should have blown up";
  } catch (const SimulationError& e) {
    EXPECT_EQ(e.step, 0);
    EXPECT_EQ(e.body, 0);
    EXPECT_EQ(e.quantity, "speed");
    EXPECT_NE(std::string(e.what()).find("step 0: body 0"), std::string::npos) << e.what();
  }
  EXPECT_EQ(sim.bodies().size(), 2);  // what was computed is still there
}
