#include "engine/integrator.hpp"

#include <algorithm>
#include <cmath>

#include "engine/forces.hpp"

namespace ballast {

namespace {

inline double sign(double v) {
  return (v > 0.0) - (v < 0.0);
}

// PFC local damping on one vector quantity; returns the damped value.
inline Vec3 local_damp(const Vec3& f, const Vec3& v, double alpha) {
  Vec3 out;
  for (int k = 0; k < 3; ++k) out[k] = f[k] - alpha * std::abs(f[k]) * sign(v[k]);
  return out;
}

}  // namespace

void integrate(const IntegratorSettings& s, const ContactList& ball_contacts,
               const ContactList& wall_contacts, const std::vector<Vec3>& reference,
               BodyStore& bodies, BallStore& balls, IntegrationReport& report) {
  const Index n = bodies.size();
  const double dt = s.dt, alpha = s.local_damping;
  const double vmax2 = s.max_speed * s.max_speed;
  Index bad = std::numeric_limits<Index>::max();
  double shift2 = 0.0;

#pragma omp for schedule(static) nowait
  for (Index b = 0; b < n; ++b) {
    gather_body_force(b, ball_contacts, wall_contacts, s.gravity, balls, bodies);
    const double m = bodies.mass[b];
    const Vec3 v_old = bodies.velocity[b], w_old = bodies.angular_velocity[b];
    const Vec3 f = alpha > 0.0 ? local_damp(bodies.force[b], v_old, alpha) : bodies.force[b];
    const Vec3 torque = alpha > 0.0 ? local_damp(bodies.torque[b], w_old, alpha) : bodies.torque[b];

    const Vec3 v_new = v_old + (dt * bodies.inv_mass[b]) * f;
    bodies.velocity[b] = v_new;
    bodies.position[b] += dt * v_new;

    Vec3 w_new;
    if (bodies.is_sphere[b]) {
      w_new = w_old + (dt * bodies.inv_inertia[b][0]) * torque;
    } else {
      RotationState rs{bodies.orientation[b], w_old, bodies.angular_momentum[b]};
      if (s.rotation == RotationIntegrator::kFull)
        rotate_full(rs, torque, bodies.inv_inertia[b], dt);
      else
        rotate_pfc(rs, torque, bodies.inv_inertia[b], dt);
      bodies.orientation[b] = rs.orientation;
      bodies.angular_momentum[b] = rs.angular_momentum;
      w_new = rs.angular_velocity;
    }
    bodies.angular_velocity[b] = w_new;
    bodies.rotation[b] += dt * w_new;

    // Energy ledger with mid-step velocities, so it matches the kinetic energy
    // change of the half-step velocities exactly: ΔKE = F·(v_old + v_new)/2·dt.
    const Vec3 v_mid = 0.5 * (v_old + v_new), w_mid = 0.5 * (w_old + w_new);
    bodies.gravity_work[b] += dt * m * s.gravity.dot(v_mid);
    if (alpha > 0.0)
      bodies.damping_dissipated[b] -=
          dt * ((f - bodies.force[b]).dot(v_mid) + (torque - bodies.torque[b]).dot(w_mid));

    // Re-place the balls and measure how far they moved since the neighbour build.
    const Index first = bodies.first_ball[b], last = first + bodies.ball_count[b];
    if (bodies.is_sphere[b]) {
      balls.position[first] = bodies.position[b];
    } else {
      const Mat3 rot = bodies.orientation[b].toRotationMatrix();
      for (Index k = first; k < last; ++k)
        balls.position[k] = bodies.position[b] + rot * balls.offset[k];
    }
    for (Index k = first; k < last; ++k)
      shift2 = std::max(shift2, (balls.position[k] - reference[k]).squaredNorm());

    const double speed2 = v_new.squaredNorm();
    if (!std::isfinite(speed2) || !std::isfinite(w_new.squaredNorm()) || speed2 > vmax2)
      bad = std::min(bad, b);
  }

  // Per-thread results combined with max/min: exact in any order, so the report
  // does not depend on the thread count.
#pragma omp critical(ballast_integrate_report)
  {
    report.max_ball_shift2 = std::max(report.max_ball_shift2, shift2);
    if (bad != std::numeric_limits<Index>::max() &&
        (report.bad_body == kNoIndex || bad < report.bad_body))
      report.bad_body = bad;
  }
#pragma omp barrier
#pragma omp single
  if (report.bad_body != kNoIndex) {
    const Index b = report.bad_body;
    report.bad_is_nan = !std::isfinite(bodies.velocity[b].squaredNorm()) ||
                        !std::isfinite(bodies.angular_velocity[b].squaredNorm());
  }
}

}  // namespace ballast
