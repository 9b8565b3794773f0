// The servo law of engine/servo.hpp, step by step:
//     u = gain·(F_target − F_measured) / (K_walls·dt + C_walls),  |u| <= max_speed,
// on scenes where its consequence is exact. Each test names the one-line mutation
// of engine/simulation_step.cpp (Simulation::drive_walls) or engine/servo.cpp it
// catches; each was applied once by hand and made the test fail.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "test_helpers.hpp"

using namespace ballast;
using ballast::test_support::expect_error;

namespace {

constexpr double kRadius = 0.02, kDt = 1e-5;
constexpr double kBallK = 1e8, kWallK = 1e8;  // N/m; in series 5e7
constexpr double kSeriesK = kBallK * kWallK / (kBallK + kWallK);

// A lid under a servo above one sphere, no gravity, no damping. The sphere is made
// so heavy (density 1e15 kg/m³, 3e10 kg) that in the steps a test runs it moves by
// less than 1e-15 m: the lid then presses on a fixed spring of stiffness kSeriesK,
// the case the law is written for. `gap` > 0 starts the lid clear of the ball,
// < 0 overlapping it by −gap.
struct LidOnSpring {
  Simulation sim;
  Index lid = 0;
};

LidOnSpring lid_on_spring(double gap, double gain, double max_speed,
                          std::function<double(double)> target, double damping_ratio = 0.0) {
  SimulationSettings s = scenes::bare_settings(0.1);  // small: a moving lid rebuilds often
  s.fixed_dt = kDt;
  s.damping_ratio = damping_ratio;
  LidOnSpring out{Simulation(s), 0};
  const Index mat = out.sim.add_material({kBallK, kBallK, 0.0});
  out.sim.add_sphere(Vec3::Zero(), kRadius, 1e15, mat);
  out.lid = out.sim.add_wall(
      scenes::plane_wall(Vec3(0, 0, kRadius + gap), -Vec3::UnitZ(), {kWallK, kWallK, 0.0}));
  Servo servo;
  servo.walls = {out.lid};
  servo.axis = -Vec3::UnitZ();
  servo.gain = gain;
  servo.max_speed = max_speed;
  servo.target_force = std::move(target);
  out.sim.add_servo(servo);
  return out;
}

// Force errors F_target − F_measured the servo saw on each of `steps` steps.
std::vector<double> errors_seen(LidOnSpring& l, int steps) {
  std::vector<double> e;
  for (int k = 0; k < steps; ++k) {
    l.sim.step();
    const Servo& s = l.sim.servos()[0];
    e.push_back(s.target_now - s.measured_force);
  }
  return e;
}

}  // namespace

// The lid moves gain·e/K in a step, which raises the spring's force by gain·e: the
// error left is (1 − gain)·e, step after step. Mutations caught: the speed without
// its 1/dt (the ratio goes to 1), the sign of the error flipped (the lid backs
// off: no contact, the ratio is undefined and the force falls), the stiffness
// summed twice per contact (ratio 1 − gain/2).
TEST(ServoLaw, ForceErrorShrinksByOneMinusGainEachStepOnASpring) {
  for (double gain : {0.25, 0.5, 0.8}) {
    // 1 µm of overlap: 50 N; the target 550 N, an error of 500 N.
    LidOnSpring l = lid_on_spring(-1e-6, gain, 100.0, [](double) { return 550.0; });
    const std::vector<double> e = errors_seen(l, 10);
    ASSERT_NEAR(e[0], 500.0, 1e-6);
    // Exact but for round-off: the lid's position (z ≈ 0.02 m) carries ~3e-18 m per
    // step, 2e-10 N on this spring; 1e-8 N allows fifty such roundings. The error
    // falls from 500 N to 500·(1 − gain)⁹ ≥ 2.6e-4 N, far above that.
    for (std::size_t k = 1; k < e.size(); ++k)
      EXPECT_NEAR(e[k], (1.0 - gain) * e[k - 1], 1e-8) << "gain " << gain << ", step " << k;
  }
}

// A dashpot on the lid's contact answers the lid's speed at once: the force the
// servo measures is K·δ + C·u. With β = 1e-6 on this 3e10 kg ball, C = 2β·√(m·K) =
// 2.6e3 N·s/m against K·dt = 500 N·s/m: a law dividing by K·dt alone overshoots by
// gain·C/(K·dt) = 2.6 times each step and chatters at max_speed (a levelling plate
// over a bed settling with dashpots did). Divided by K·dt + C, the error obeys
// e' = (1 − g)·e + g·φ·e_prev with φ = C/(K·dt + C) = 0.84: roots 0.944 and −0.444,
// so 400 steps take it below 1e-6 of its start, with no step at the cap.
// Mutation caught: C left out of the law (tests/mutations.tsv).
TEST(ServoLaw, DashpotOnTheContactDoesNotMakeTheLidChatter) {
  LidOnSpring l = lid_on_spring(
      -1e-6, 0.5, 1.0, [](double) { return 550.0; }, 1e-6);
  const std::vector<double> e = errors_seen(l, 400);
  ASSERT_NEAR(e[0], 500.0, 1e-6);
  EXPECT_LT(std::abs(e.back()), 1e-6 * 500.0);
  // The slow root dominates: the error keeps its sign and shrinks by 0.944 a step
  // (the recurrence above, exact in the first steps; by step 100 the error is 1.6 N,
  // far above what the ball's creep under 550 N changes, ~1e-8 N).
  EXPECT_NEAR(e[100] / e[99], 0.944, 0.001);
  EXPECT_LT(std::abs(l.sim.servos()[0].speed), 1.0);
}

// gain = 1 removes the whole error in one step, on a spring.
TEST(ServoLaw, GainOneRemovesTheErrorInOneStep) {
  LidOnSpring l = lid_on_spring(-1e-6, 1.0, 100.0, [](double) { return 550.0; });
  const std::vector<double> e = errors_seen(l, 3);
  EXPECT_NEAR(e[0], 500.0, 1e-6);
  EXPECT_NEAR(e[1], 0.0, 1e-9);
  EXPECT_NEAR(e[2], 0.0, 1e-9);
}

// With no contact the stiffness is zero: the lid goes towards the bed at max_speed,
// exactly max_speed·dt per step, and away from it when the target asks for less
// than nothing. Mutations caught: max_speed replaced by the clamp's other bound (the
// lid goes the wrong way), the no-contact branch's sign flipped.
TEST(ServoLaw, LidTouchingNothingMovesMaxSpeedTimesDtEachStep) {
  for (double target : {100.0, -100.0}) {
    LidOnSpring l = lid_on_spring(0.01, 0.5, 0.3, [=](double) { return target; });
    const double z0 = l.sim.walls()[l.lid].point.z();
    for (int k = 1; k <= 100; ++k) {
      l.sim.step();
      ASSERT_EQ(l.sim.servos()[0].measured_force, 0.0);
      // Down (along the axis −z) to push, up to pull.
      const double expected = z0 - (target > 0 ? 1.0 : -1.0) * 0.3 * kDt * k;
      EXPECT_NEAR(l.sim.walls()[l.lid].point.z(), expected, 1e-15) << "step " << k;
    }
    EXPECT_EQ(l.sim.servos()[0].speed, target > 0 ? 0.3 : -0.3);
  }
}

// In contact, an error the law would answer with more than max_speed is answered
// with max_speed: 1e6 N on a 5e7 N/m spring asks for 1000 m/s.
// Mutation caught: the clamp dropped.
TEST(ServoLaw, SpeedIsCappedAtMaxSpeedInContact) {
  LidOnSpring l = lid_on_spring(-1e-6, 0.5, 0.3, [](double) { return 1e6; });
  const double z0 = l.sim.walls()[l.lid].point.z();
  l.sim.step();
  EXPECT_GT(l.sim.servos()[0].measured_force, 0.0);
  EXPECT_EQ(l.sim.servos()[0].speed, 0.3);
  EXPECT_NEAR(l.sim.walls()[l.lid].point.z(), z0 - 0.3 * kDt, 1e-15);
  // The spring's force rose by K·max_speed·dt = 150 N.
  const double f0 = l.sim.servos()[0].measured_force;
  l.sim.step();
  EXPECT_NEAR(l.sim.servos()[0].measured_force - f0, kSeriesK * 0.3 * kDt, 1e-6);
}

// The target is read at the time of the step: a sine is followed, not its start.
// Mutation caught: target_force evaluated at t = 0 instead of the step's time.
TEST(ServoLaw, TargetIsReadAtTheStepsTime) {
  LidOnSpring l = lid_on_spring(-1e-6, 1.0, 100.0, sinusoidal_load(100.0, 900.0, 50.0, 0.0));
  for (int k = 0; k < 200; ++k) l.sim.step();
  const Servo& s = l.sim.servos()[0];
  EXPECT_NEAR(s.target_now, sinusoidal_load(100.0, 900.0, 50.0, 0.0)(l.sim.time() - kDt), 1e-9);
  // gain 1 on a fixed spring: one step behind a target that moves at most
  // 400 N · 2π · 50 Hz · 1e-5 s = 1.26 N per step.
  EXPECT_LT(std::abs(s.target_now - s.measured_force), 1.5);
}

TEST(ServoLaw, BadSettingsAreRefusedNamingTheField) {
  const auto add = [](auto change) {
    Simulation sim(scenes::bare_settings());
    const Index w = sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), {1e6, 1e6, 0}));
    Servo s;
    s.walls = {w};
    s.target_force = [](double) { return 1.0; };
    change(s);
    sim.add_servo(s);
  };
  expect_error([&] { add([](Servo& s) { s.gain = 0.0; }); }, {"servo gain", "0", "(0, 1]"});
  expect_error([&] { add([](Servo& s) { s.gain = 1.5; }); }, {"servo gain", "1.5", "(0, 1]"});
  expect_error([&] { add([](Servo& s) { s.max_speed = -1.0; }); },
               {"servo max_speed", "-1", "> 0 m/s"});
  expect_error([&] { add([](Servo& s) { s.axis = Vec3(0, 0, 2); }); },
               {"servo axis length", "2", "unit vector"});
  expect_error([&] { add([](Servo& s) { s.walls = {}; }); }, {"servo walls (count)", "0"});
  expect_error([&] { add([](Servo& s) { s.walls = {5}; }); }, {"servo wall index", "5", "0..0"});
  expect_error([&] { add([](Servo& s) { s.target_force = nullptr; }); },
               {"servo target_force", "a function of time"});
}
