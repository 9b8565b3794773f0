#include "cases/bed.hpp"

#include <cmath>
#include <random>
#include <utility>

#include "cases/sphere_packing.hpp"
#include "engine/clump_batch.hpp"

namespace ballast {

Quat uniform_rotation(double u1, double u2, double u3) {
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double t2 = 2.0 * kPi * u2, t3 = 2.0 * kPi * u3;
  return Quat(b * std::cos(t3), a * std::sin(t2), a * std::cos(t2), b * std::sin(t3)).normalized();
}

namespace {

// Each clump's generation frame (central ball at the origin, the frame the virtual
// sphere is centred in) is put at a packing centre p with a random rotation Q. A
// ball at x_gen = gc + G·offset then sits at p + Q·x_gen, so the body's centre of
// mass is p + Q·gc and its principal frame is Q·G.
void add_clumps(Simulation& sim, const BedOptions& o, const std::vector<Vec3>& centres, Index mat) {
  ClumpParams params = *o.clumps;
  params.nominal_diameter = o.diameter;
  ClumpMassOptions mass = o.mass;
  mass.density = box_test::kDensity;
  const std::vector<ClumpTemplate> templates =
      generate_clump_templates(params, mass, centres.size(), o.seed);
  std::mt19937_64 rng(o.seed ^ 0x5851f42d4c957f2dull);
  for (std::size_t k = 0; k < centres.size(); ++k) {
    const ClumpTemplate& t = templates[k];
    const double u1 = unit_uniform(rng()), u2 = unit_uniform(rng()), u3 = unit_uniform(rng());
    const Quat turn = uniform_rotation(u1, u2, u3);
    const Vec3 x = centres[k] + turn * t.generation_centre;
    const Quat q = turn * Quat(t.generation_rotation);
    sim.add_clump(x, q, t, mat);
  }
}

}  // namespace

Simulation make_bed(const BedOptions& o) {
  const double r = 0.5 * o.diameter;
  // The cloud is packed by the spheres that bound each particle.
  const double bound = o.clumps ? r * o.clumps->virtual_sphere_factor : r;
  const Vec3 lo = Vec3::Zero();
  const Vec3 hi(o.length, o.width, kBedDomainTop);
  SimulationSettings s = o.sim;
  // The domain reaches one bound past the walls so a ball pressed into a wall is
  // still inside it.
  s.domain_lo = lo - Vec3::Constant(2.0 * bound);
  s.domain_hi = hi + Vec3::Constant(2.0 * bound);
  Simulation sim(s);
  // Balls and side walls share one material (for Hertz–Mindlin, granite's moduli);
  // the base is rubber or the same.
  const Material stiff{o.stiffness, o.stiffness, o.friction, box_test::kBallastYoungModulus,
                       box_test::kBallastPoissonRatio};
  const Index mat = sim.add_material(stiff);
  const Material base = o.rubber_base ? box_test::rubber_base(o.friction) : stiff;
  for (const Wall& w : box_container(lo, hi, stiff, base, /*open_top=*/true)) sim.add_wall(w);
  std::vector<Vec3> centres =
      o.centres.empty() ? random_loose_packing(o.count, bound, lo, hi, o.volume_fraction, o.seed)
                        : o.centres;
  if (!o.spatial_order) {
    // Fisher–Yates with the bed's own seed: the same bed, bodies numbered at random.
    std::mt19937_64 rng(o.seed ^ 0x9e3779b97f4a7c15ull);
    for (std::size_t k = centres.size(); k > 1; --k)
      std::swap(centres[k - 1], centres[static_cast<std::size_t>(unit_uniform(rng()) * k)]);
  }
  if (o.clumps) {
    add_clumps(sim, o, centres, mat);
  } else {
    for (const Vec3& p : centres) sim.add_sphere(p, r, box_test::kDensity, mat);
  }
  if (o.engine_sort) sim.sort_bodies_spatially(/*always=*/true);
  return sim;
}

}  // namespace ballast
