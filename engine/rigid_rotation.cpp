#include "engine/rigid_rotation.hpp"

#include <cmath>

#include "engine/errors.hpp"

namespace ballast {

namespace {

// The body turns by angle θ about its own principal axis `axis`, with the world
// angular momentum held fixed: the body-frame components lb then turn by −θ about
// that axis. θ = h·lb[axis]/I[axis] is exact because lb[axis] does not change.
inline void principal_sub_rotation(int axis, double h, const Vec3& inv_inertia, Vec3& lb,
                                   Quat& q) {
  const double theta = h * lb[axis] * inv_inertia[axis];
  if (theta == 0.0) return;
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  const double c = std::cos(theta), s = std::sin(theta);
  const double li = lb[i], lj = lb[j];
  lb[i] = c * li + s * lj;
  lb[j] = -s * li + c * lj;
  Quat dq(std::cos(0.5 * theta), 0.0, 0.0, 0.0);
  dq.vec()[axis] = std::sin(0.5 * theta);
  q = q * dq;
}

}  // namespace

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
