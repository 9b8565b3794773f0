#include "engine/walls.hpp"

#include <cmath>

#include "engine/contact_laws.hpp"
#include "engine/errors.hpp"
#include "engine/ordered_pairs.hpp"

namespace ballast {

WallTouch touch_wall(const Wall& w, const Vec3& x, double r) {
  if (w.shape == WallShape::Plane) {
    const double s = w.normal.dot(x - w.point);  // signed distance of the centre
    return {r - s, w.normal, x - s * w.normal};
  }
  // Solid box with edges rounded to re: the points within re of the core box
  // [lo + re, hi - re]. The closest core point is the centre clamped into the core;
  // the surface lies re beyond it. With re = 0 every term below is the sharp box's to
  // the bit (x + 0.0 == x).
  const double re = w.edge_radius;
  const Vec3 core_lo = w.lo.array() + re, core_hi = w.hi.array() - re;
  const Vec3 c = x.cwiseMax(core_lo).cwiseMin(core_hi);
  const Vec3 d = x - c;
  const double dist2 = d.squaredNorm();
  if (dist2 > 0.0) {
    const double dist = std::sqrt(dist2);
    const Vec3 n = d / dist;
    return {(r + re) - dist, n, c + re * n};
  }
  // Centre inside the core (deep penetration): push out through the nearest face.
  const Vec3 to_lo = x - core_lo, to_hi = core_hi - x;
  int axis = 0;
  double depth = to_lo[0];
  Vec3 n = -Vec3::UnitX();
  for (int a = 0; a < 3; ++a) {
    if (to_lo[a] < depth) depth = to_lo[a], axis = a, n = -Vec3::Unit(a);
    if (to_hi[a] < depth) depth = to_hi[a], axis = a, n = Vec3::Unit(a);
  }
  Vec3 p = x;
  p[axis] = n[axis] < 0 ? w.lo[axis] : w.hi[axis];
  return {(r + re) + depth, n, p};
}

void find_wall_candidates(const std::vector<Wall>& walls, const std::vector<Vec3>& positions,
                          const std::vector<double>& radii, double skin,
                          std::vector<Index>& out_ball, std::vector<Index>& out_wall) {
  const Index nw = static_cast<Index>(walls.size());
  const auto scan = [&](Index lo, Index hi, std::vector<Index>& balls, std::vector<Index>& ws) {
    for (Index k = lo; k < hi; ++k)
      for (Index w = 0; w < nw; ++w)
        if (touch_wall(walls[w], positions[k], radii[k] + skin).overlap > 0.0) {
          balls.push_back(k);
          ws.push_back(w);
        }
  };
  collect_pairs_in_order(static_cast<Index>(positions.size()), scan, out_ball, out_wall);
}

void advance_wall(Wall& w, double dt) {
  const Vec3 step = w.velocity * dt;
  w.point += step;
  w.lo += step;
  w.hi += step;
  w.displacement += step;
}

std::vector<Wall> box_container(const Vec3& lo, const Vec3& hi, const Material& sides,
                                const Material& base, bool open_top) {
  std::vector<Wall> walls;
  auto plane = [&](const char* name, const Vec3& p, const Vec3& n, const Material& m) {
    Wall w;
    w.name = name;
    w.shape = WallShape::Plane;
    w.point = p;
    w.normal = n;
    w.material = m;
    walls.push_back(w);
  };
  plane("xmin", lo, Vec3::UnitX(), sides);
  plane("xmax", hi, -Vec3::UnitX(), sides);
  plane("ymin", lo, Vec3::UnitY(), sides);
  plane("ymax", hi, -Vec3::UnitY(), sides);
  plane("base", lo, Vec3::UnitZ(), base);
  if (!open_top) plane("lid", hi, -Vec3::UnitZ(), sides);
  return walls;
}

void validate_wall(const Wall& w, int law) {
  const std::string f = "wall '" + w.name + "' ";
  check_law_parameters(law, w.material, f);
  require_setup(w.material.mu >= 0.0 && std::isfinite(w.material.mu), f + "mu", w.material.mu,
                ">= 0");
  if (w.shape == WallShape::Plane) {
    require_setup(std::abs(w.normal.norm() - 1.0) < 1e-9, f + "normal length", w.normal.norm(),
                  "1 (a unit vector)");
    require_setup(w.edge_radius == 0.0, f + "edge_radius of a plane", w.edge_radius,
                  "0 (only a box has edges)");
  } else {
    const double side = (w.hi - w.lo).minCoeff();
    require_setup(side > 0.0, f + "box extent (hi - lo, smallest)", side, "> 0 m");
    require_setup(w.edge_radius >= 0.0 && 2.0 * w.edge_radius < side, f + "edge_radius",
                  w.edge_radius, "in [0, half the box's smallest side) m");
  }
  if (w.motion == WallMotion::Fixed)
    require_setup(w.velocity.isZero(0.0), f + "velocity of a fixed wall", w.velocity.norm(),
                  "0 (use WallMotion::Prescribed to move it)");
}

}  // namespace ballast
