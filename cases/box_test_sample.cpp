#include "cases/box_test_sample.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>
#include <random>
#include <string>

#include "cases/bed.hpp"
#include "cases/packing_bodies.hpp"
#include "cases/sphere_packing.hpp"
#include "engine/ball_union_integral.hpp"
#include "engine/clump_batch.hpp"
#include "engine/errors.hpp"

namespace ballast {

namespace {

// The scene's numerics in a domain that holds the box up to twice its height, with
// room `bound` (m, the largest particle's bounding radius) around it; weightless.
SimulationSettings settings_for(const BoxTestScene& s, double bound) {
  SimulationSettings st = s.sim;
  st.domain_lo = -Vec3::Constant(2.0 * bound);
  st.domain_hi = Vec3(s.length, s.width, 2.0 * s.height) + Vec3::Constant(2.0 * bound);
  st.gravity = Vec3::Zero();
  return st;
}

// The box's walls, with a lid (the last wall) at `lid` m while particles grow.
void add_walls(Simulation& sim, const BoxTestScene& s, double lid, double mu) {
  const Material sides = box_test::with_friction(s.wall, mu);
  const Material base = box_test::with_friction(s.base, mu);
  for (const Wall& w : box_container(Vec3::Zero(), Vec3(s.length, s.width, lid), sides, base,
                                     /*open_top=*/false))
    sim.add_wall(w);
}

// Growing particles gain speed (a chain of n touching balls spreads at n times the
// growth rate), so growth happens weightless in a closed box with inelastic
// contacts (dashpots, β = 0.5), at a loose porosity where nothing jams, and the
// gas of particles is brought to rest (quenched) before the lid goes and gravity
// comes.
constexpr double kGrowthDampingRatio = 0.5;

// Grows every particle from `from` to full size, the largest ball's radius growing at
// `speed` m/s.
StageReport grow(Simulation& sim, const std::string& name, double from, double speed,
                 std::ostream* log) {
  const auto start = std::chrono::steady_clock::now();
  const double t0 = sim.time();
  double largest = 0.0;
  for (double r : sim.balls().radius) largest = std::max(largest, r);
  sim.set_size_scale(from);
  sim.prepare();
  const EnergyBudget e0 = sim.energy();
  const long steps = std::max(1L, std::lround((1.0 - from) * largest / (speed * sim.dt())));
  for (long k = 1; k <= steps; ++k) {
    sim.set_size_scale(from + (1.0 - from) * double(k) / double(steps));
    sim.step();
  }
  StageReport r{name, steps, sim.time() - t0, stage_seconds(start), sim.unbalanced_force_ratio(),
                ""};
  r.book_energy(e0, sim.energy());
  print_stage(log, r, sim);
  return r;
}

// Mean volume of the union of each clump's balls over (at most) the first 256
// templates, m³: the space a clump really takes, overlaps counted once. 2 % accuracy
// per clump is ample for sizing a fill region.
double mean_clump_volume(const std::vector<ClumpTemplate>& templates) {
  const std::size_t n = std::min<std::size_t>(templates.size(), 256);
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const ClumpTemplate& t = templates[k];
    sum += t.mass_mode == MassMode::kUniform ? t.volume
                                             : ball_union_moments(t.offsets, t.radii, 0.02).volume;
  }
  return sum / double(n);
}

}  // namespace

// Stages 1-2: the sample generated and grown under a lid, which is then lifted away.
PreparedBed generate_sample(const BoxTestScene& s, std::ostream* log) {
  const double r = nominal_radius(s);
  const double sphere_volume = 4.0 / 3.0 * kPi * r * r * r;
  const double area = s.length * s.width;
  // Clump samples: the templates come first, because their own volume sizes the fill
  // region. A clump filling 0.55-0.6 of a virtual sphere 1.26-1.31 times the nominal
  // radius is 1.1-1.3 times the nominal sphere's volume (Table 2 Samples 1 and 2), so
  // clumps grown in the places of spheres packed at porosity n0 would sit at a solid
  // fraction of up to 0.66: jammed in the closed box, with overlaps of a millimetre
  // that exploded when the lid went. The spheres are therefore generated looser, so
  // that the clumps replacing them fill the region at the initial porosity.
  std::vector<ClumpTemplate> templates;
  double particle_volume = sphere_volume;
  if (s.clumps) {
    const ClumpMassOptions mass{s.mass_mode, s.simulated_density(), s.mass_accuracy};
    templates =
        generate_clump_templates(*s.clumps, mass, static_cast<std::size_t>(s.count), s.seed);
    particle_volume = std::max(sphere_volume, mean_clump_volume(templates));
  }
  // Stage 1: the fill region holds the particles at the initial porosity once grown.
  const double fill = s.count * particle_volume / ((1.0 - s.initial_porosity) * area);
  // The walls are infinite planes, so the loose fill may rise above the box; it
  // settles into it. Twice the box height is the domain's limit.
  require_setup(fill <= 1.8 * s.height, "particle count", s.count,
                "few enough to fill at most 1.8 box heights at the initial porosity (needs " +
                    std::to_string(fill) + " m, box height " + std::to_string(s.height) + " m)");
  // Random addition stalls near a volume fraction of 0.38: generate at a radius
  // giving 0.3 at most.
  double shrink = std::min(0.9, std::cbrt(0.3 / (1.0 - s.initial_porosity)));
  const auto rsa_fraction = [&](double k) {
    return s.count * sphere_volume * k * k * k / (area * std::max(fill - 2.0 * k * r, k * r));
  };
  while (rsa_fraction(shrink) > 0.3) shrink *= 0.98;  // thin fill regions lose 2r to walls
  const double rs = shrink * r;
  const double fraction = rsa_fraction(shrink);
  const std::vector<Vec3> centres = random_loose_packing(
      static_cast<int>(s.count), rs, Vec3::Zero(), Vec3(s.length, s.width, fill), fraction, s.seed);
  if (log)
    *log << "stage 1: " << s.count << " spheres of " << s.diameter * 1e3 << " mm generated at "
         << shrink << " of full radius in a " << s.length * 1e3 << " x " << s.width * 1e3 << " x "
         << fill * 1e3 << " mm region (initial porosity " << s.initial_porosity
         << (s.clumps ? " of the clumps to come; spheres at " +
                            std::to_string(1.0 - s.count * sphere_volume / (fill * area))
                      : std::string())
         << ")\n";

  PreparedBed out{Simulation(settings_for(s, r)), {}, 0.0, {}};
  {
    // Frictionless while growing; friction comes with compaction.
    Simulation& sim = out.sim;
    sim.set_damping_ratio(kGrowthDampingRatio);
    const Index mat = sim.add_material(box_test::with_friction(s.ball, 0.0));
    add_walls(sim, s, fill, 0.0);
    for (const Vec3& p : centres) sim.add_sphere(p, r, s.simulated_density(), mat);
    out.stages.push_back(grow(sim, "expand", shrink, s.expansion_speed, log));
    sim.quench();  // the grown gas at rest at once, instead of cycling it cool
    out.dt_spheres = sim.dt();
  }

  if (s.clumps) {
    // Stage 2: clumps in the spheres' places, shrunk by 1/factor so each lies inside
    // its sphere, then grown back under gravity with the lid gone.
    const ClumpParams& p = *s.clumps;
    const double bound = r * p.virtual_sphere_factor;
    Simulation sim(settings_for(s, bound));
    const Index mat = sim.add_material(box_test::with_friction(s.ball, 0.0));
    add_walls(sim, s, fill, 0.0);
    sim.set_damping_ratio(kGrowthDampingRatio);
    std::mt19937_64 rng(s.seed ^ 0x5851f42d4c957f2dull);
    long balls = 0;
    double mass = 0.0;  // kg, for the log: the mode's weight against the nominal sphere's
    for (Index k = 0; k < out.sim.bodies().size(); ++k) {
      const ClumpTemplate& t = templates[static_cast<std::size_t>(k)];
      mass += t.mass;
      const double u1 = unit_uniform(rng()), u2 = unit_uniform(rng()), u3 = unit_uniform(rng());
      const Quat turn = uniform_rotation(u1, u2, u3);
      const Vec3 centre = out.sim.bodies().position[k];
      // The clump grows from 1/factor of its size about its centre of mass: place the
      // centre of mass so that the shrunk clump's generation origin (its virtual
      // sphere's centre) sits on the sphere's centre, where the shrunk clump lies
      // inside the sphere and so touches nothing. Placing it for full size instead
      // put shrunk clumps up to (1 - 1/factor)·|generation centre| off their spheres,
      // into their neighbours.
      sim.add_clump(centre + (1.0 / p.virtual_sphere_factor) * (turn * t.generation_centre),
                    turn * Quat(t.generation_rotation), t, mat);
      balls += t.ball_count();
    }
    if (log)
      *log << "stage 2: " << s.count << " clumps of " << s.shape << " (" << balls
           << " balls, mass mode " << mass_mode_name(s.mass_mode) << ", rotation "
           << rotation_integrator_name(s.sim.rotation) << ", mean volume "
           << particle_volume / sphere_volume << " and mean mass "
           << mass / (s.count * s.simulated_density() * sphere_volume)
           << " x the nominal sphere's) replace the spheres\n";
    out.stages.push_back(
        grow(sim, "clumps", 1.0 / p.virtual_sphere_factor, s.expansion_speed, log));
    sim.quench();
    out.sim = std::move(sim);
    out.templates = std::move(templates);  // kept for the run's archive
  }
  out.sim.set_damping_ratio(0.0);
  return out;  // the lid still on, at the fill height
}

// The imported packing stands for stages 1-2: the box without a lid, frictionless
// until compaction brings friction, like a generated sample.
PreparedBed import_sample(const BoxTestScene& s, std::ostream* log) {
  Packing packing;
  try {
    packing = read_packing_file(s.packing_file);
  } catch (const SetupError& e) {
    throw SetupError(std::string("/particles/file: ") + e.what());
  }
  const PackingMass mass{{s.mass_mode, s.simulated_density(), s.mass_accuracy}, s.diameter};
  PreparedBed out{Simulation(settings_for(s, packing_body_size(packing))), {}, 0.0, {}};
  Simulation& sim = out.sim;
  const Index mat = sim.add_material(box_test::with_friction(s.ball, 0.0));
  const Material sides = box_test::with_friction(s.wall, 0.0);
  const Material base = box_test::with_friction(s.base, 0.0);
  // A lid just above the bed's top, where a levelling plate is asked for (it is
  // lifted off otherwise, as a generated sample's).
  double top = 0.0;
  for (std::size_t k = 0; k < packing.centre.size(); ++k)
    top = std::max(top, packing.centre[k].z() + packing.radius[k]);
  for (const Wall& w : box_container(Vec3::Zero(), Vec3(s.length, s.width, top + 1e-3), sides, base,
                                     /*open_top=*/false))
    sim.add_wall(w);
  add_packing(sim, packing, mass, mat);
  // A file from another code comes in its order: numbered cell by cell when that pays.
  const SpatialOrder order = sim.sort_bodies_spatially();
  if (log)
    *log << "stages 1-2: " << packing.bodies() << " " << (packing.clumps ? "clumps" : "spheres")
         << " (" << packing.balls() << " balls, mass mode " << mass_mode_name(s.mass_mode)
         << ") imported from " << s.packing_file << "; " << describe(order) << "\n";
  return out;
}

}  // namespace ballast
