#include "cases/sphere_bed.hpp"

#include "cases/sphere_packing.hpp"

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
  const Index mat = sim.add_material({o.stiffness, o.stiffness, o.friction});
  const Material side{o.stiffness, o.stiffness, o.friction};
  const Material base = o.rubber_base ? box_test::rubber_base(o.friction)
                                      : Material{o.stiffness, o.stiffness, o.friction};
  for (const Wall& w : box_container(lo, hi, side, base, /*open_top=*/true)) sim.add_wall(w);
  for (const Vec3& p : random_loose_packing(o.count, r, lo, hi, o.volume_fraction, o.seed))
    sim.add_sphere(p, r, box_test::kDensity, mat);
  return sim;
}

}  // namespace ballast
