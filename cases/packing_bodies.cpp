#include "cases/packing_bodies.hpp"

#include <algorithm>
#include <cmath>

#include "engine/errors.hpp"

namespace ballast {

ClumpTemplate packing_clump_template(const Packing& p, Index body, const PackingMass& m) {
  const Index first = p.body_first[body], last = p.body_first[body + 1];
  const std::vector<Vec3> centres(p.centre.begin() + first, p.centre.begin() + last);
  const std::vector<double> radii(p.radius.begin() + first, p.radius.begin() + last);
  const double r = 0.5 * m.nominal_diameter;
  const double v_clump = 4.0 / 3.0 * kPi * r * r * r;  // eq 10's V_clump (paper mode only)
  try {
    const MassProperties mp = clump_mass_properties(centres, radii, m.mass, v_clump);
    return to_principal_frame(centres, radii, mp, m.mass.mode);
  } catch (const SetupError& e) {
    throw SetupError(p.where(first) + ": body " + std::to_string(p.body_id[body]) + ": " +
                     e.what());
  }
}

Index add_packing(Simulation& sim, const Packing& p, const PackingMass& m, Index material) {
  const Index first_body = sim.bodies().size();
  for (Index b = 0; b < p.bodies(); ++b) {
    const Index k = p.body_first[b];
    try {
      if (p.ball_count(b) == 1) {
        sim.add_sphere(p.centre[k], p.radius[k], m.mass.density, material);
      } else {
        const ClumpTemplate t = packing_clump_template(p, b, m);
        sim.add_clump(t.generation_centre, Quat(t.generation_rotation), t, material);
      }
    } catch (const SetupError& e) {
      const std::string what = e.what();
      // Messages from the template already point into the file.
      if (what.rfind(p.where(k), 0) == 0) throw;
      throw SetupError(p.where(k) + ": " + what);
    }
  }
  return first_body;
}

double packing_body_size(const Packing& p) {
  double size = 0.0;
  for (Index b = 0; b < p.bodies(); ++b) {
    const Index first = p.body_first[b], last = p.body_first[b + 1];
    Vec3 mean = Vec3::Zero();
    for (Index k = first; k < last; ++k) mean += p.centre[k];
    mean /= double(last - first);
    for (Index k = first; k < last; ++k)
      size = std::max(size, 2.0 * ((p.centre[k] - mean).norm() + p.radius[k]));
  }
  return size;
}

Packing packing_of(const Simulation& sim) {
  const BodyStore& bodies = sim.bodies();
  const BallStore& balls = sim.balls();
  Packing p;
  p.clumps = !std::all_of(bodies.is_sphere.begin(), bodies.is_sphere.end(),
                          [](std::uint8_t s) { return s != 0; });
  p.centre.reserve(static_cast<std::size_t>(balls.size()));
  p.radius.reserve(static_cast<std::size_t>(balls.size()));
  for (Index b = 0; b < bodies.size(); ++b) {
    const Index first = bodies.first_ball[b], last = first + bodies.ball_count[b];
    for (Index k = first; k < last; ++k) {
      p.centre.push_back(balls.position[k]);
      p.radius.push_back(balls.radius[k]);
      p.line.push_back(0);
    }
    p.body_first.push_back(p.balls());
    p.body_id.push_back(b);
  }
  return p;
}

}  // namespace ballast
