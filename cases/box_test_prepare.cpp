#include "cases/box_test_prepare.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>

#include "cases/bed.hpp"
#include "cases/box_test_sample.hpp"

namespace ballast {

double stage_seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

void print_stage(std::ostream* log, const StageReport& r, const Simulation& sim) {
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

namespace {

// Contact dashpots (β) of the frictionless settling, which local damping would hold
// almost still (continue_box_test_preparation).
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
  r.seconds = stage_seconds(start);
  r.unbalanced = sim.unbalanced_force_ratio();
  r.book_energy(e0, sim.energy());
  print_stage(log, r, sim);
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
  r.seconds = stage_seconds(start);
  r.unbalanced = sim.unbalanced_force_ratio();
  r.book_energy(e0, sim.energy());
  print_stage(log, r, sim);
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
  if (due(PrepStage::kPrepared)) {
    if (at.plate) {
      lift();
      // The top rebounds a little from the plate's pressure: settle again.
      out.stages.push_back(settle(sim, "plate off", s.equilibrium_ratio, s.max_stage_steps, log));
      at.plate = false;
    }
    reached(PrepStage::kPrepared);
  }
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
