// The two rotation integrators on a torque-free asymmetric body: `full` must keep
// the angular momentum to round-off and the energy to 1e-6, show the
// intermediate-axis (Dzhanibekov) flip, and follow an independent RK4 solution of
// Euler's equations to within its O((ω·dt)²) error; `pfc` (eq 17 without the
// gyroscopic term) is measured, and its defect asserted so that it cannot silently
// change.
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

// ---- An independent reference: Euler's equations by classical RK4 ----
//
// Torque-free, in the principal frame: I1 ω1' = (I2 − I3) ω2 ω3 and cyclic. The
// orientation q (principal frame → world) follows q' = ½ q ⊗ (0, ω), and the
// accumulated rotation vector (what the box test reports as particle rotation)
// follows θ' = ω in the world frame. Nothing of the engine is used.
struct Attitude {
  Vec3 w;                      // rad/s, principal frame
  Eigen::Vector4d q;           // (w, x, y, z) of the quaternion principal frame → world
  Vec3 turned = Vec3::Zero();  // ∫ω dt, world frame, rad
};

Quat as_quat(const Eigen::Vector4d& q) {
  return Quat(q[0], q[1], q[2], q[3]).normalized();
}

Attitude attitude_rate(const Attitude& a) {
  const Vec3& i = kInertia;
  const Vec3& w = a.w;
  const Vec3 dw((i[1] - i[2]) * w[1] * w[2] / i[0], (i[2] - i[0]) * w[2] * w[0] / i[1],
                (i[0] - i[1]) * w[0] * w[1] / i[2]);
  // q ⊗ (0, ω) = (−v·ω, s ω + v × ω) for q = (s, v).
  const double s = a.q[0];
  const Vec3 v = a.q.tail<3>();
  Eigen::Vector4d dq;
  dq[0] = -v.dot(w);
  dq.tail<3>() = s * w + v.cross(w);
  return {dw, 0.5 * dq, as_quat(a.q) * w};
}

Attitude rk4_step(const Attitude& a, double h) {
  const auto plus = [](const Attitude& x, double c, const Attitude& d) {
    return Attitude{x.w + c * d.w, x.q + c * d.q, x.turned + c * d.turned};
  };
  const Attitude k1 = attitude_rate(a);
  const Attitude k2 = attitude_rate(plus(a, 0.5 * h, k1));
  const Attitude k3 = attitude_rate(plus(a, 0.5 * h, k2));
  const Attitude k4 = attitude_rate(plus(a, h, k3));
  Attitude sum = plus(k1, 2.0, k2);
  sum = plus(sum, 2.0, k3);
  sum = plus(sum, 1.0, k4);
  return plus(a, h / 6.0, sum);
}

// Angle of the rotation that takes orientation a to b, rad.
double angle_between(const Quat& a, const Quat& b) {
  const Quat d = a.conjugate() * b;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

// Time at which x, sampled x_prev at t − h and x at t, crosses zero; linear
// interpolation, s.
double crossing_time(double t, double h, double x_prev, double x) {
  return t - h * x / (x - x_prev);
}

// How far the engine's `full` body strays from the reference (maxima over all steps).
struct Deviation {
  double spin = 0.0;         // |ω − ω_ref| / |ω(0)|, principal frame
  double orientation = 0.0;  // angle from the reference orientation to the engine's, rad
  // The accumulated rotation Σ ω·dt sums ω at the end of each step (`full` derives
  // ω from the orientation after the step): the right-endpoint rule, which is
  // ∫ω dt + (dt/2)(ω(t) − ω(0)) + O(dt²) (Euler–Maclaurin). `lag` is that
  // first-order term, `turned` what is left after taking it off, both rad.
  double turned = 0.0;
  double lag = 0.0;
  double flip_time = -1.0;            // first time ω_y crosses zero downwards, s (−1: never)
  double reference_flip_time = -1.0;  // the same for the reference, s
};

// Steps the engine and, in lock-step, the reference (RK4 at a tenth of the engine's
// step), comparing after every engine step.
Deviation follow_reference(const Vec3& w_body, double dt, long steps) {
  constexpr int kSubsteps = 10;
  const double h = dt / kSubsteps;
  FreeBody body(RotationIntegrator::kFull, w_body, dt);
  const BodyStore& bodies = body.sim.bodies();
  const Quat& q0 = kStartOrientation;
  const Vec3 w0_world = q0 * w_body;
  Attitude ref{w_body, Eigen::Vector4d(q0.w(), q0.x(), q0.y(), q0.z())};
  Deviation d;
  double wy_prev = w_body.y();
  for (long k = 1; k <= steps; ++k) {
    body.sim.step();
    for (int j = 1; j <= kSubsteps; ++j) {
      const Attitude next = rk4_step(ref, h);
      if (d.reference_flip_time < 0.0 && ref.w.y() > 0.0 && next.w.y() <= 0.0)
        d.reference_flip_time =
            crossing_time(((k - 1) * kSubsteps + j) * h, h, ref.w.y(), next.w.y());
      ref = next;
    }
    const Vec3 w = body.body_spin();
    if (d.flip_time < 0.0 && wy_prev > 0.0 && w.y() <= 0.0)
      d.flip_time = crossing_time(k * dt, dt, wy_prev, w.y());
    wy_prev = w.y();
    d.spin = std::max(d.spin, (w - ref.w).norm() / w_body.norm());
    d.orientation = std::max(d.orientation, angle_between(as_quat(ref.q), body.orientation()));
    const Vec3 lag = 0.5 * dt * (bodies.angular_velocity[body.b] - w0_world);
    d.lag = std::max(d.lag, lag.norm());
    d.turned = std::max(d.turned, (bodies.rotation[body.b] - lag - ref.turned).norm());
  }
  return d;
}

void print(const char* label, const Deviation& d) {
  std::printf(
      "%-14s |dw|/w %.3e, orientation %.3e rad, rotation vector %.3e rad (lag %.3e rad),\n"
      "%-14s first w_y = 0 at %.9f s, RK4 %.9f s, difference %.2e s\n",
      label, d.spin, d.orientation, d.turned, d.lag, "", d.flip_time, d.reference_flip_time,
      d.flip_time - d.reference_flip_time);
}

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

// `full` against the RK4 reference. Conserving L and E (above) is nearly true by
// construction; this checks the motion itself. The reference's own error: at dt/10
// and dt/20 it agrees to 2.4e-12 in ω/|ω| and 2.8e-12 rad in orientation (round-off,
// grown through the flip) over 1e6 RK4 steps, so what is measured is the engine's.
// The splitting's error is O((ω·dt)²) per unit time, ω·dt = 2e-4 rad: the bounds
// are the figures measured at kDt times 3, and doubling dt multiplies them by 4.
//
// One-line mutations these two tests fail under, the tests above do not:
//  - rigid_rotation.cpp, principal_sub_rotation: θ = −h·lb[axis]/I[axis] (the body
//    turns backwards: the time-reversed motion keeps L and E and still flips);
//    ω and orientation off by 2|ω| and π rad.
//  - integrator.cpp: rotate_full(…, 0.99 * dt): a 1 % slow clock keeps L and E;
//    orientation 0.2 rad off, the flip 11 ms late.
//  - integrator.cpp: accumulated rotation += dt·w_old instead of dt·w_new: the
//    rotation vector off by dt·Δω, 1e-4 rad against a bound of 3e-8 rad.
// And, with the tests above: s = −2·s2·c2 (the body-frame L turned the wrong way),
// h = dt instead of dt/2, the 3-axis turn over h instead of dt, the order
// 1,2,3,1,1, the moment of the next axis in θ, the sign of q.w()'s update, lb or ω
// taken with q instead of q⁻¹ (rigid_rotation.cpp); L set from ω with the identity
// orientation (simulation.cpp, set_body_angular_velocity).
// Not caught: q.normalize() dropped (|q| drifts by round-off only), and −1/5 for
// −1/6 in small_angle_sin_cos's series (8e-10 rad over the run;
// SmallAngleSineAndCosineAgreeWithLibm catches it).
namespace {

// The deviations from the reference within three times what was measured (ω as a
// fraction of |ω|, orientation and rotation vector in rad), and the rotation
// vector's right-endpoint lag below dt·|ω| = 2e-4 rad (measured 5.7e-5 rad, 0.003°,
// where box-test clumps turn by about 1° during loading).
void expect_within_three_times(const Deviation& d, double spin, double orientation, double turned) {
  EXPECT_LT(d.spin, 3.0 * spin);
  EXPECT_LT(d.orientation, 3.0 * orientation);
  EXPECT_LT(d.turned, 3.0 * turned);
  EXPECT_LT(d.lag, kDt * kOmega);
}

}  // namespace

TEST(RigidRotation, FullTracksAnRk4ReferenceThroughTheFlip) {
  const Deviation d = follow_reference(kNearMiddleAxis, kDt, kSteps);
  print("full, middle:", d);
  // Measured: ω 1.154e-8 of |ω|, orientation 1.152e-8 rad, rotation vector 9.91e-9
  // rad, over ω·t = 20 rad through the flip; (ω·dt)² = 4e-8.
  expect_within_three_times(d, 1.154e-8, 1.152e-8, 9.91e-9);
  // The flip (RK4: 1.0917 s, 10.9 rad in): ω_y'' vanishes where ω_y does (ω1' and
  // ω3' are ∝ ω2), so the linear interpolation between steps is third-order there
  // and the 1.99e-9 s measured is the splitting's phase error, 1e-4 of a step.
  ASSERT_GT(d.reference_flip_time, 1.0);
  EXPECT_NEAR(d.flip_time, d.reference_flip_time, 3.0 * 1.99e-9);
  // Second order: twice the step, four times the error (measured 4.001).
  const Deviation d2 = follow_reference(kNearMiddleAxis, 2.0 * kDt, kSteps / 2);
  print("full, 2 dt:", d2);
  EXPECT_NEAR(d2.spin / d.spin, 4.0, 0.2);
}

TEST(RigidRotation, FullTracksAnRk4ReferenceForAnObliqueSpin) {
  const Deviation d = follow_reference(kOblique, kDt, kSteps);
  print("full, oblique:", d);
  // Measured: ω 9.29e-10 of |ω| (this orbit, about the major axis, is stable: no
  // separatrix to amplify the phase error), orientation 8.45e-9 rad, rotation
  // vector 8.27e-9 rad.
  expect_within_three_times(d, 9.29e-10, 8.45e-9, 8.27e-9);
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
