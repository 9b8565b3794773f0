#include "cases/sphere_bed.hpp"

#include "cases/sphere_packing.hpp"

#include <random>
#include <utility>

namespace ballast {

Simulation make_sphere_bed(const SphereBedOptions& o) {
  const double r = 0.5 * o.diameter;
  const Vec3 lo = Vec3::Zero();
  const Vec3 hi(o.length, o.width, kBedDomainTop);
  SimulationSettings s;
  // The domain reaches one diameter past the walls so a ball pressed into a wall
  // is still inside it.
  s.domain_lo = lo - Vec3::Constant(o.diameter);
  s.domain_hi = hi + Vec3::Constant(o.diameter);
  s.gravity = o.gravity;
  s.local_damping = o.local_damping;
  s.damping_ratio = o.damping_ratio;
  s.dt_safety = o.dt_safety;
  s.log = o.log;
  Simulation sim(s);
  // Balls and side walls share one material; the base is rubber or the same.
  const Material stiff{o.stiffness, o.stiffness, o.friction};
  const Index mat = sim.add_material(stiff);
  const Material base = o.rubber_base ? box_test::rubber_base(o.friction) : stiff;
  for (const Wall& w : box_container(lo, hi, stiff, base, /*open_top=*/true)) sim.add_wall(w);
  std::vector<Vec3> centres = random_loose_packing(o.count, r, lo, hi, o.volume_fraction, o.seed);
  if (!o.spatial_order) {
    // Fisher–Yates with the bed's own seed: the same bed, bodies numbered at random.
    std::mt19937_64 rng(o.seed ^ 0x9e3779b97f4a7c15ull);
    for (std::size_t k = centres.size(); k > 1; --k)
      std::swap(centres[k - 1], centres[static_cast<std::size_t>(unit_uniform(rng()) * k)]);
  }
  for (const Vec3& p : centres) sim.add_sphere(p, r, box_test::kDensity, mat);
  return sim;
}

}  // namespace ballast
