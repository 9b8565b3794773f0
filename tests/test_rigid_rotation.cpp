// The two rotation integrators on a torque-free asymmetric body: `full` must keep
// the angular momentum to round-off and the energy to 1e-6 and show the
// intermediate-axis (Dzhanibekov) flip; `pfc` (eq 17 without the gyroscopic term)
// is measured, and its defect asserted so that it cannot silently change.
// Figures printed here are quoted in docs/TRADEOFFS.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "test_helpers.hpp"

using namespace ballast;

namespace {

// Principal moments 1 : 2 : 3 (times m·r²): every axis distinct, the middle one
// unstable with growth rate ω·sqrt((I2−I1)(I3−I2)/(I1·I3)) = 0.58·ω.
constexpr double kMass = 0.05, kRadius = 0.01;
const Vec3 kInertia = kMass * kRadius * kRadius * Vec3(1.0, 2.0, 3.0);

struct FreeSpin {
  double max_momentum_error = 0.0;    // max |L(t) − L(0)| / |L(0)|, L = R·I·Rᵀ·ω
  double max_magnitude_error = 0.0;   // max ||L(t)| − |L(0)|| / |L(0)|
  double max_energy_error = 0.0;      // max |E(t) − E(0)| / E(0)
  double min_middle_axis_spin = 0.0;  // min of ω along the body's intermediate axis, rad/s
};

// Where every free body starts: tilted, so that no principal axis is a world axis.
const Quat kStartOrientation(Eigen::AngleAxisd(0.4, Vec3(1, 1, 0).normalized()));

// A two-ball body given the moments above (the balls only make it a clump, they
// never touch anything), spinning at w_body (rad/s, principal frame) from
// kStartOrientation.
struct FreeBody {
  Simulation sim;
  Index b;

  FreeBody(RotationIntegrator rotation, const Vec3& w_body, double dt)
      : sim(settings(rotation, dt)) {
    const Index mat = sim.add_material({1e6, 1e6, 0.0});
    const std::vector<Vec3> offsets{Vec3(-0.01, 0, 0), Vec3(0.01, 0, 0)};
    const std::vector<double> radii{0.005, 0.005};
    b = sim.add_clump(Vec3::Zero(), kStartOrientation, offsets, radii, kMass, kInertia, mat);
    sim.set_body_angular_velocity(b, kStartOrientation * w_body);
    sim.prepare();
  }
  static SimulationSettings settings(RotationIntegrator rotation, double dt) {
    // A 10 cm box: the balls sweep round, so the neighbour search is rebuilt every
    // few hundred steps, and clearing the cells of the default 2 m box took 3/4 of
    // the run time.
    SimulationSettings s = scenes::bare_settings(0.05);
    s.fixed_dt = dt;
    s.rotation = rotation;
    return s;
  }
  // Principal frame → world.
  const Quat& orientation() const { return sim.bodies().orientation[b]; }
  // ω in the principal frame, rad/s.
  Vec3 body_spin() const { return orientation().conjugate() * sim.bodies().angular_velocity[b]; }
};

FreeSpin spin_free_body(RotationIntegrator rotation, const Vec3& w_body, double dt, long steps) {
  FreeBody body(rotation, w_body, dt);
  Simulation& sim = body.sim;
  const Index b = body.b;
  const BodyStore& bodies = sim.bodies();
  const auto momentum = [&] {
    return spin_angular_momentum(bodies.orientation[b], kInertia, bodies.angular_velocity[b]);
  };
  const Vec3 l0 = momentum();
  const double e0 = sim.energy().kinetic_rotational;
  FreeSpin r;
  r.min_middle_axis_spin = w_body.y();
  for (long k = 0; k < steps; ++k) {
    sim.step();
    const Vec3 l = momentum();
    r.max_momentum_error = std::max(r.max_momentum_error, (l - l0).norm() / l0.norm());
    r.max_magnitude_error =
        std::max(r.max_magnitude_error, std::abs(l.norm() - l0.norm()) / l0.norm());
    r.max_energy_error =
        std::max(r.max_energy_error, std::abs(sim.energy().kinetic_rotational - e0) / e0);
    r.min_middle_axis_spin = std::min(r.min_middle_axis_spin, body.body_spin().y());
  }
  return r;
}

// ω·dt = 2e-4 rad per step; 1e5 steps are 20 rad, two to three flips.
constexpr double kOmega = 10.0, kDt = 2e-5;
constexpr long kSteps = 100000;
// 1 % off the intermediate axis: the flip comes after ~ln(100)/0.58 ≈ 8 rad.
const Vec3 kNearMiddleAxis = kOmega * Vec3(0.01, 1.0, 0.01);
// Far from every principal axis: Iω and ω differ in direction by 22.2°.
const Vec3 kOblique = kOmega * Vec3(1.0, 1.0, 1.0).normalized();

void print(const char* label, const FreeSpin& r) {
  std::printf("%-14s |dL|/L %.2e, d|L|/L %.2e, dE/E %.2e, min middle-axis spin %.3f rad/s\n", label,
              r.max_momentum_error, r.max_magnitude_error, r.max_energy_error,
              r.min_middle_axis_spin);
}

}  // namespace

TEST(RigidRotation, FullConservesAngularMomentumAndEnergyAndFlips) {
  const FreeSpin r = spin_free_body(RotationIntegrator::kFull, kNearMiddleAxis, kDt, kSteps);
  print("full, middle:", r);
  // L is the integrator's state and no torque acts: only the round-off of turning
  // it into the body frame and back (~1e-15 per step, not accumulated) remains.
  EXPECT_LT(r.max_momentum_error, 1e-10);
  EXPECT_LT(r.max_magnitude_error, 1e-10);
  // The splitting's energy error is bounded at O((ω·dt)²) = O(4e-8).
  EXPECT_LT(r.max_energy_error, 1e-6);
  // Dzhanibekov: the spin about the intermediate axis reverses (it is +10 rad/s at
  // the start and swings to about −10 rad/s).
  EXPECT_LT(r.min_middle_axis_spin, -0.9 * kOmega);
}

TEST(RigidRotation, FullConservesAnObliqueSpinToo) {
  const FreeSpin r = spin_free_body(RotationIntegrator::kFull, kOblique, kDt, kSteps);
  print("full, oblique:", r);
  EXPECT_LT(r.max_momentum_error, 1e-10);
  EXPECT_LT(r.max_energy_error, 1e-6);
}

// Without ω×Iω a torque-free body turns about a fixed world axis at constant ω:
// its body-frame ω is frozen, so |L| and E stay (to round-off) but L itself turns
// with the body (Iω is not parallel to ω off a principal axis), and the
// intermediate-axis flip never comes.
TEST(RigidRotation, PfcNeverFlips) {
  const FreeSpin r = spin_free_body(RotationIntegrator::kPfc, kNearMiddleAxis, kDt, kSteps);
  print("pfc, middle:", r);
  EXPECT_GT(r.min_middle_axis_spin, 0.99 * kOmega);
  EXPECT_LT(r.max_energy_error, 1e-9);
}

TEST(RigidRotation, PfcTurnsTheAngularMomentumOfAnObliqueSpin) {
  const FreeSpin r = spin_free_body(RotationIntegrator::kPfc, kOblique, kDt, kSteps);
  print("pfc, oblique:", r);
  EXPECT_LT(r.max_magnitude_error, 1e-9);
  EXPECT_LT(r.max_energy_error, 1e-9);
  // L = R·I·ω_body sweeps a cone of half-angle 22.2° about ω: |ΔL|/|L| reaches
  // the cone's diameter, 2·sin 22.2° = 0.756, half a turn in.
  EXPECT_NEAR(r.max_momentum_error, 0.756, 0.005);
}

// The `full` integrator's sine and cosine agree with libm to within one ulp of the
// result over the series' whole range (both are within about half an ulp of the
// true value), and are libm's own beyond it.
TEST(RigidRotation, SmallAngleSineAndCosineAgreeWithLibm) {
  constexpr double kUlp = 0x1p-52;
  double worst_sin = 0.0, worst_cos = 0.0;
  for (int k = -4000; k <= 4000; ++k) {
    const double x = k * (0x1p-5 / 4001.0);  // |x| < 2⁻⁵, the series
    double s, c;
    small_angle_sin_cos(x, s, c);
    if (x != 0.0)
      worst_sin = std::max(worst_sin, std::abs(s - std::sin(x)) / std::abs(std::sin(x)));
    worst_cos = std::max(worst_cos, std::abs(c - std::cos(x)));
  }
  EXPECT_LE(worst_sin, kUlp);
  EXPECT_LE(worst_cos, kUlp);
  double s, c;
  small_angle_sin_cos(0.5, s, c);  // beyond the series: libm itself
  EXPECT_EQ(s, std::sin(0.5));
  EXPECT_EQ(c, std::cos(0.5));
}
