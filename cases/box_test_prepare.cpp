#include "cases/box_test_prepare.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <random>
#include <stdexcept>

#include "cases/bed.hpp"
#include "cases/packing_bodies.hpp"
#include "cases/sphere_packing.hpp"
#include "engine/ball_union_integral.hpp"
#include "engine/clump_batch.hpp"
#include "engine/errors.hpp"

namespace ballast {

namespace {

double elapsed(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

void print(std::ostream* log, const StageReport& r, const Simulation& sim) {
  if (!log) return;
  const ContactStats c = sim.contacts();
  char line[240];
  std::snprintf(line, sizeof line,
                "  %-10s %8ld steps %8.4f s simulated %7.1f s wall  unbalanced %.1e%s  "
                "contacts %ld  Z %.2f\n",
                r.name.c_str(), r.steps, r.simulated, r.seconds, r.unbalanced,
                r.ended_by.empty() ? "" : (" (" + r.ended_by + ")").c_str(),
                c.ball_contacts + c.wall_contacts, c.coordination);
  *log << line << std::flush;
}

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
constexpr double kSettleDampingRatio = 0.3;

Index lid_of(const Simulation& sim) {
  return static_cast<Index>(sim.walls().size()) - 1;
}

// The lid as a levelling plate: a servo presses it on the bed's top with the scene's
// levelling pressure over the whole box, so that the top settles against a plane.
// It moves at up to kPlateSpeed: a bed settling under 10 g falls away from it faster
// than the sleeper's 0.5 m/s would follow (a Sample 1 bed fell 100 mm in 0.17 s).
constexpr double kPlateSpeed = 1.0;  // m/s

std::function<double(double)> plate_target(const BoxTestScene& s) {
  const double force = s.levelling_pressure * s.length * s.width;
  return [force](double) { return force; };
}

Index press_lid(Simulation& sim, const BoxTestScene& s) {
  Servo plate;
  plate.walls = {lid_of(sim)};
  plate.axis = -Vec3::UnitZ();
  plate.target_force = plate_target(s);
  plate.gain = s.sleeper_gain;
  plate.max_speed = kPlateSpeed;
  return sim.add_servo(plate);
}

bool lid_touches(const Simulation& sim) {
  const Index lid = lid_of(sim);
  const ContactList& c = sim.wall_contacts();
  for (Index k = 0; k < c.size(); ++k)
    if (c.active[k] && c.b[k] == lid) return true;
  return false;
}

// A plate that the settling bed has left behind is let down to 1 mm above its top at
// once (no contact opens, so no work goes unbooked), as the sleeper is placed.
void lower_plate(Simulation& sim, const BoxTestScene& s) {
  if (lid_touches(sim)) return;
  const Index lid = lid_of(sim);
  const double top = bed_top(sim, 0.0, s.length);
  const double gap = sim.walls()[lid].point.z() - (top + 1e-3);
  if (gap > 0.0) sim.move_wall(lid, Vec3(0, 0, -gap));
}

// Lifts the plate off the bed: its servo unloads it along a ramp to zero over
// kUnloadTime, booking the work the bed's top does on it as it rebounds, until it
// holds 1e-3 of its load; then it stops and is put out of reach (what its contacts
// still hold then, (1e-3 F)²/2k over a hundred contacts, is nothing). Released at
// once instead, a smoke-scale Sample 1 bed sprang up and did not come back to rest
// within 400,000 steps; unloaded by a servo with a target of zero it took 190,000
// steps at full scale, as slowly as the soft rubber base lets the bed rebound.
constexpr double kUnloadTime = 0.01;  // s

StageReport lift_plate(Simulation& sim, Index servo, const BoxTestScene& s, std::ostream* log) {
  const auto start = std::chrono::steady_clock::now();
  const double t0 = sim.time();
  const EnergyBudget e0 = sim.energy();
  const Index lid = lid_of(sim);
  const double load = s.levelling_pressure * s.length * s.width;
  sim.set_servo_target(
      servo, [load, t0](double t) { return load * std::max(0.0, 1.0 - (t - t0) / kUnloadTime); });
  StageReport r{"lift plate", 0, 0.0, 0.0, 0.0, "step limit"};
  for (r.steps = 1; r.steps <= s.max_stage_steps; ++r.steps) {
    sim.step();
    if (sim.time() >= t0 + kUnloadTime && sim.servos()[servo].measured_force <= 1e-3 * load) {
      r.ended_by = "unloaded";
      break;
    }
  }
  r.steps = std::min(r.steps, s.max_stage_steps);
  sim.release_servo(servo);
  sim.move_wall(lid, Vec3(0, 0, s.height));
  r.simulated = sim.time() - t0;
  r.seconds = elapsed(start);
  r.unbalanced = sim.unbalanced_force_ratio();
  r.book_energy(e0, sim.energy());
  print(log, r, sim);
  return r;
}

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
  StageReport r{name, steps, sim.time() - t0, elapsed(start), sim.unbalanced_force_ratio(), ""};
  r.book_energy(e0, sim.energy());
  print(log, r, sim);
  return r;
}

}  // namespace

StageReport settle(Simulation& sim, const std::string& name, double ratio, long max_steps,
                   std::ostream* log, SettleRule rule, const std::function<double()>& depth) {
  if (rule == SettleRule::kSeated && !depth)
    throw std::invalid_argument("settle(): SettleRule::kSeated needs the sleeper's depth");
  const auto start = std::chrono::steady_clock::now();
  const double t0 = sim.time();
  // kKinetic: at rest when the kinetic energy is below 1e-4 of the bed's potential
  // energy above the base (a frictionless bed never reaches a low force ratio: its
  // rattlers and sliding contacts keep it near 0.3-0.6).
  double potential = 0.0;
  for (Index b = 0; b < sim.bodies().size(); ++b)
    potential += sim.bodies().mass[b] * -sim.settings().gravity.z() *
                 std::max(0.0, sim.bodies().position[b].z());
  // kSeated: the sleeper's depth at the end of the last window and its creep over it.
  const long window = std::max(2000L, std::lround(kSettleWindow / sim.dt()));
  double depth_then = rule == SettleRule::kSeated ? depth() : 0.0, creep_then = 0.0;
  long windows = 0;
  // A bed without contacts is falling, not balanced, whatever its force ratio.
  const auto touching = [&sim] { return 2 * sim.contacts().ball_contacts >= sim.bodies().size(); };
  const EnergyBudget e0 = sim.energy();
  StageReport r{name, 0, 0.0, 0.0, 0.0, "step limit"};
  for (r.steps = 1; r.steps <= max_steps; ++r.steps) {
    sim.step();
    if (rule == SettleRule::kSeated && r.steps % window == 0) {
      // Steady creep: what creep remains goes on however long the seating lasts, and
      // the load cycle measures its settlement from where the seating ends.
      const double now = depth(), creep = now - depth_then;
      const bool steady = ++windows >= 2 && creep_then > 0.0 && creep >= kSteadyCreep * creep_then;
      depth_then = now;
      creep_then = creep;
      if (steady && sim.unbalanced_force_ratio() < kQuasiStaticRatio && touching()) {
        r.ended_by = "steady creep";
        break;
      }
    }
    if (r.steps < 2000 || r.steps % 500 != 0) continue;
    if (rule == SettleRule::kKinetic) {
      if (sim.energy().kinetic() < 1e-4 * potential) {
        r.ended_by = "at rest";
        break;
      }
      continue;
    }
    // kRatio and kSeated: the unbalanced-force ratio.
    if (sim.unbalanced_force_ratio() < ratio && touching()) {
      r.ended_by = "equilibrium";
      break;
    }
  }
  r.steps = std::min(r.steps, max_steps);
  r.simulated = sim.time() - t0;
  r.seconds = elapsed(start);
  r.unbalanced = sim.unbalanced_force_ratio();
  r.book_energy(e0, sim.energy());
  print(log, r, sim);
  return r;
}

double bed_top(const Simulation& sim, double x0, double x1) {
  // Every ball that reaches over the strip counts, not only those centred in it: a
  // ball centred just outside rises over the strip's edge up to z + sqrt(r² − dx²),
  // dx its centre's distance from the strip. Counting only centres inside put the
  // sleeper into such a ball by millimetres (Sample 2 at smoke scale blew up seven
  // steps after the sleeper came).
  double top = 0.0;
  const BallStore& b = sim.balls();
  for (Index k = 0; k < b.size(); ++k) {
    const double x = b.position[k].x(), r = b.radius[k];
    const double dx = std::max({0.0, x0 - x, x - x1});
    if (dx < r) top = std::max(top, b.position[k].z() + std::sqrt(r * r - dx * dx));
  }
  return top;
}

namespace {

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
    for (Index k = 0; k < out.sim.bodies().size(); ++k) {
      const ClumpTemplate& t = templates[static_cast<std::size_t>(k)];
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
           << particle_volume / sphere_volume << " x the nominal sphere's) replace the spheres\n";
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

}  // namespace

void continue_box_test_preparation(const BoxTestScene& s, PreparedBed& out, PrepPoint at,
                                   std::ostream* log, const PrepCheckpoint& at_point) {
  Simulation& sim = out.sim;
  // A servo's target is a function, which a checkpoint cannot hold: the plate's again.
  if (at.plate) sim.set_servo_target(at.plate_servo, plate_target(s));
  const auto reached = [&](PrepStage stage) {
    at.done = stage;
    if (at_point) at_point(out, at);
  };
  const auto due = [&](PrepStage stage) { return at.done < stage; };
  // A plate that never reached the bed (an imported packing stopped before any step)
  // is put away without a stage: nothing bears on it, and the bed stays as it came.
  const auto lift = [&] {
    if (!at.plate) return;
    if (lid_touches(sim)) {
      out.stages.push_back(lift_plate(sim, at.plate_servo, s, log));
      return;
    }
    sim.release_servo(at.plate_servo);
    sim.move_wall(lid_of(sim), Vec3(0, 0, s.height));
  };
  if (due(PrepStage::kSettled)) {
    if (s.frictionless_settling) {
      // The sample settles into its dense state still frictionless, as a radius-
      // expansion sample is meant to reach its porosity before loading starts; under
      // the compaction gravity with contact dashpots. Local damping would hold a
      // frictionless bed almost still: at α = 0.7 the full-scale bed's porosity went
      // from 0.49 to 0.47 in 0.45 s, against 0.49 to 0.41 in 0.19 s with dashpots.
      sim.set_local_damping(0.0);
      sim.set_damping_ratio(kSettleDampingRatio);
      sim.set_gravity(Vec3(0, 0, s.gravity(s.gravity_factor)));
      out.stages.push_back(
          settle(sim, "settle", s.equilibrium_ratio, s.max_stage_steps, log, SettleRule::kKinetic));
      sim.set_damping_ratio(0.0);
      sim.set_local_damping(s.sim.local_damping);
    }
    sim.set_all_friction(s.friction_compaction);
    reached(PrepStage::kSettled);
  }
  if (s.stop_after == "prepare") {
    lift();
    return;
  }

  // Stage 3: compaction.
  if (due(PrepStage::kCompacted)) {
    if (log) *log << "stage 3: compaction at " << s.gravity_factor << " g, then 1 g\n";
    sim.set_gravity(Vec3(0, 0, s.gravity(s.gravity_factor)));
    if (at.plate) lower_plate(sim, s);
    out.stages.push_back(settle(sim, "compact", s.equilibrium_ratio, s.max_stage_steps, log));
    reached(PrepStage::kCompacted);
  }
  if (due(PrepStage::kAtOneG)) {
    sim.set_gravity(Vec3(0, 0, s.gravity(1.0)));
    out.stages.push_back(settle(sim, "1 g", s.equilibrium_ratio, s.max_stage_steps, log));
    reached(PrepStage::kAtOneG);
  }
  if (due(PrepStage::kFrictionRaised)) {
    sim.set_all_friction(s.friction_loading);
    out.stages.push_back(settle(sim, "mu=" + std::to_string(s.friction_loading).substr(0, 4),
                                s.equilibrium_ratio, s.max_stage_steps, log));
    reached(PrepStage::kFrictionRaised);
  }
  if (!at.plate) return;
  lift();
  // The top rebounds a little from the plate's pressure: settle again.
  out.stages.push_back(settle(sim, "plate off", s.equilibrium_ratio, s.max_stage_steps, log));
}

PreparedBed prepare_box_test(const BoxTestScene& s, std::ostream* log,
                             const PrepCheckpoint& at_point) {
  PreparedBed out = s.packing_file.empty() ? generate_sample(s, log) : import_sample(s, log);
  // The lid: a levelling plate through compaction, or lifted off now.
  PrepPoint at;
  if (s.levelling_pressure > 0.0) {
    at.plate = true;
    at.plate_servo = press_lid(out.sim, s);
    if (log)
      *log << "levelling plate on the bed's top at " << s.levelling_pressure * 1e-3
           << " kPa through compaction\n";
  } else {
    out.sim.move_wall(lid_of(out.sim), Vec3(0, 0, s.height));
  }
  at.done = PrepStage::kGenerated;
  if (at_point) at_point(out, at);
  continue_box_test_preparation(s, out, at, log, at_point);
  return out;
}

}  // namespace ballast
