#include "engine/body_store.hpp"

namespace ballast {

Index BodyStore::add(const Vec3& x, const Quat& q, double m, const Vec3& principal_inertia,
                     Index first, Index count, bool sphere) {
  position.push_back(x);
  velocity.push_back(Vec3::Zero());
  angular_velocity.push_back(Vec3::Zero());
  angular_momentum.push_back(Vec3::Zero());
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
  orientation.push_back(q.normalized());
  mass.push_back(m);
  inv_mass.push_back(1.0 / m);
  inertia.push_back(principal_inertia);
  inv_inertia.push_back(principal_inertia.cwiseInverse());
  first_ball.push_back(first);
  ball_count.push_back(count);
  is_sphere.push_back(sphere ? 1 : 0);
  reference_position.push_back(x);
  rotation.push_back(Vec3::Zero());
  gravity_work.push_back(0.0);
  damping_dissipated.push_back(0.0);
  return size() - 1;
}

void BodyStore::reset_motion_reference() {
  reference_position = position;
  for (Vec3& r : rotation) r.setZero();
}

}  // namespace ballast
