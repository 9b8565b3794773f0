#include "engine/sphere_planes.hpp"

namespace ballast {

void fill_plane_table(const std::vector<Wall>& walls, PlaneTable& t) {
  t.other_shapes = false;
  t.rows.assign(kPlaneRow * walls.size(), 0.0);
  t.is_plane.assign(walls.size(), 0);
  bool any_plane = false, planes_first = true;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (walls[w].shape != WallShape::Plane) {
      t.other_shapes = true;
      continue;
    }
    planes_first = planes_first && !t.other_shapes;
    any_plane = true;
    t.is_plane[w] = 1;
    double* const row = t.rows.data() + kPlaneRow * w;
    for (int q = 0; q < 3; ++q) {
      row[q] = walls[w].normal[q];
      row[3 + q] = walls[w].point[q];
      row[6 + q] = walls[w].velocity[q];
    }
  }
  t.planes_in_lanes = any_plane && planes_first;
}

SpherePlaneView sphere_plane_view(const SphereKernelView& k, const PlaneTable& planes,
                                  const PairTable& pairs, ContactList& wall_contacts, bool friction,
                                  bool ledger) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Wrench) == 6 * sizeof(double));
  ContactList& wc = wall_contacts;
  SpherePlaneView p;
  p.position = k.position;
  p.radius = k.radius;
  p.velocity = k.velocity;
  p.angular_velocity = k.angular_velocity;
  p.material = k.material;
  p.pair = &pairs.wall(0, 0).normal;
  p.walls = static_cast<std::int32_t>(planes.is_plane.size());
  p.plane = planes.rows.data();
  p.is_plane = planes.is_plane.data();
  p.dt = k.dt;
  p.a = wc.a.data();
  p.b = wc.b.data();
  p.shear_force = friction ? flat(wc.shear_force) : nullptr;
  p.b_wrench = wc.b_wrench.data()->force.data();
  p.normal_force = wc.normal_force.data();
  p.slip_total = ledger ? wc.slip_total.data() : nullptr;
  p.active = wc.active.data();
  p.a_side = k.a_side;
  return p;
}

}  // namespace ballast
