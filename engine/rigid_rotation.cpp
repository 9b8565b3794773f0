#include "engine/rigid_rotation.hpp"

#include <cmath>

#include "engine/errors.hpp"

namespace ballast {

namespace {

// The body turns by angle θ about its own principal axis `axis`, with the world
// angular momentum held fixed: the body-frame components lb then turn by −θ about
// that axis. θ = h·lb[axis]/I[axis] is exact because lb[axis] does not change.
// One sine and cosine, of θ/2, serve both: the quaternion of the turn is
// (cos θ/2, sin θ/2 · e_axis), and sin θ = 2 sin(θ/2) cos(θ/2), cos θ = 1 − 2 sin²(θ/2).
inline void principal_sub_rotation(int axis, double h, const Vec3& inv_inertia, Vec3& lb, Quat& q) {
  const double theta = h * lb[axis] * inv_inertia[axis];
  if (theta == 0.0) return;
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  double s2, c2;
  small_angle_sin_cos(0.5 * theta, s2, c2);
  const double s = 2.0 * s2 * c2, c = 1.0 - 2.0 * s2 * s2;
  const double li = lb[i], lj = lb[j];
  lb[i] = c * li + s * lj;
  lb[j] = -s * li + c * lj;
  // q ← q·(c2, s2·e_axis), written out: the turn's quaternion has one vector
  // component, so the product needs 8 multiplications instead of 16.
  const double w = q.w();
  const Vec3 v = q.vec();
  q.w() = c2 * w - s2 * v[axis];
  q.vec()[axis] = c2 * v[axis] + s2 * w;
  q.vec()[i] = c2 * v[i] + s2 * v[j];
  q.vec()[j] = c2 * v[j] - s2 * v[i];
}

}  // namespace

// For |x| < 2⁻⁵ the first terms left out, x⁹/9! and x⁸/8!, are below 2⁻⁵⁸ of the
// result. libm's sincos was 40 % of the `full` integrator's instructions in the
// Sample 1 bench bed (docs/PERFORMANCE.md, "What bought what").
void small_angle_sin_cos(double x, double& s, double& c) {
  if (std::abs(x) < 0x1p-5) {
    const double x2 = x * x;
    s = x + (x * x2) * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0)));
    c = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0)));
  } else {
    s = std::sin(x);
    c = std::cos(x);
  }
}

const char* rotation_integrator_name(RotationIntegrator r) {
  return r == RotationIntegrator::kFull ? "full" : "pfc";
}

RotationIntegrator parse_rotation_integrator(std::string_view name) {
  if (name == "pfc") return RotationIntegrator::kPfc;
  if (name == "full") return RotationIntegrator::kFull;
  require_setup(false, "rotation integrator", std::string(name), "\"pfc\" or \"full\"");
  return RotationIntegrator::kPfc;
}

void rotate_pfc(RotationState& s, const Vec3& torque, const Vec3& inv_inertia, double dt) {
  const Mat3 rot = s.orientation.toRotationMatrix();
  const Vec3 w_body = rot.transpose() * s.angular_velocity;
  const Vec3 m_body = rot.transpose() * torque;
  s.angular_velocity = rot * (w_body + dt * inv_inertia.cwiseProduct(m_body));
  const double angle = s.angular_velocity.norm() * dt;
  if (angle > 0.0) {
    const Quat dq(Eigen::AngleAxisd(angle, s.angular_velocity / (angle / dt)));
    s.orientation = (dq * s.orientation).normalized();
  }
}

void rotate_full(RotationState& s, const Vec3& torque, const Vec3& inv_inertia, double dt) {
  s.angular_momentum += dt * torque;  // world frame: exact for M = 0
  Quat q = s.orientation;
  Vec3 lb = q.conjugate() * s.angular_momentum;
  const double h = 0.5 * dt;
  principal_sub_rotation(0, h, inv_inertia, lb, q);
  principal_sub_rotation(1, h, inv_inertia, lb, q);
  principal_sub_rotation(2, dt, inv_inertia, lb, q);
  principal_sub_rotation(1, h, inv_inertia, lb, q);
  principal_sub_rotation(0, h, inv_inertia, lb, q);
  q.normalize();
  s.orientation = q;
  // ω from the stored L and the new orientation, so ω, L and q stay consistent.
  s.angular_velocity = q * inv_inertia.cwiseProduct(q.conjugate() * s.angular_momentum);
}

}  // namespace ballast
