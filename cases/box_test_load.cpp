#include "cases/box_test_load.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>

#include "cases/box_test_checkpoint.hpp"
#include "cases/box_test_zones.hpp"
#include "cases/contact_census.hpp"
#include "cases/cycle_recorder.hpp"
#include "cases/duration_text.hpp"
#include "engine/clump_shape.hpp"
#include "engine/errors.hpp"
#include "engine/porosity.hpp"

namespace ballast {

namespace {

constexpr double kDeg = 180.0 / kPi;

// The load cycle's energy budget must close to this fraction of the larger of what went
// in and what was dissipated, or its measurements are the integrator's, not the
// bed's. Measured on tiny.json at every setting of tests/cli/test_extremes.py that
// runs: at most 0.98 % (clumps with c = 0.99), 0.64 % (Hertz-Mindlin), the others
// 0.27 %; on the smoke and full-scale scenes 0.006-0.014 %; at a fixed dt of twice the
// critical estimate, 56 % (docs/ACCURACY.md).
constexpr double kMaxCycleEnergyError = 0.05;

// s: how often a run of many cycles logs its progress.
constexpr double kProgressSeconds = 60.0;

// Throws SimulationError when the cycle's budget does not close, naming the timestep
// against its critical estimate, the knob that breaks it.
void check_cycle_energy(const Simulation& sim, const StageReport& cycle) {
  const double scale = std::max(std::abs(cycle.energy_in), cycle.energy_dissipated);
  const double error = std::abs(cycle.energy_error);
  if (error <= kMaxCycleEnergyError * scale) return;  // a NaN fails this and is refused
  char what[400];
  std::snprintf(what, sizeof what,
                "step %ld: the load cycle's energy budget is off by %.3g J, %.0f %% of the %.3g J "
                "it turned over (allowed: %.0f %%): its measurements would be the integrator's. "
                "dt = %.4g s is %.2f x the critical estimate %.4g s (/numerics/dt, "
                "/numerics/dt_safety)",
                sim.step_count(), cycle.energy_error, 100.0 * error / scale, scale,
                100.0 * kMaxCycleEnergyError, sim.dt(), sim.dt() / sim.critical_dt(),
                sim.critical_dt());
  throw SimulationError(sim.step_count(), -1, "energy", what);
}

// Rotation angles (deg) of the accumulated rotation vectors a − b.
std::vector<double> angles(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  std::vector<double> out(a.size());
  for (std::size_t k = 0; k < a.size(); ++k) out[k] = (a[k] - b[k]).norm() * kDeg;
  return out;
}

RotationStats stats_of(const std::vector<double>& deg) {
  RotationStats s;
  for (double d : deg) {
    s.mean_deg += d;
    s.max_deg = std::max(s.max_deg, d);
  }
  if (!deg.empty()) s.mean_deg /= double(deg.size());
  return s;
}

double max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, (a[k] - b[k]).norm());
  return m;
}

void measure_porosity(const BoxTestScene& s, const Simulation& sim, double x0, double x1,
                      double bottom, BoxTestResult& out) {
  out.bed_height = bottom;
  out.porosity_grid =
      grid_porosity(sim.balls(), Vec3(x0, 0.0, 0.0), Vec3(x1, s.width, bottom), s.cube_side)
          .porosity;
  // The same grid one nominal diameter away from the side walls, the base and the
  // bed's top: the layers a flat boundary loosens are left out (the paper does not
  // say whether its column kept them). NaN where the column is too thin for it.
  const double d = s.diameter;
  out.porosity_grid_interior = std::numeric_limits<double>::quiet_NaN();
  if (s.width - 2.0 * d >= s.cube_side && bottom - 2.0 * d >= s.cube_side)
    out.porosity_grid_interior =
        grid_porosity(sim.balls(), Vec3(x0, d, d), Vec3(x1, s.width - d, bottom - d), s.cube_side)
            .porosity;
  // Measurement spheres count the overlaps inside a clump twice: spheres only
  // (decided by the bodies, so that an imported packing is judged by what it holds).
  const auto& is_sphere = sim.bodies().is_sphere;
  if (std::find(is_sphere.begin(), is_sphere.end(), 0) != is_sphere.end()) return;
  const double r = std::min({s.sphere_radius, 0.5 * s.width, 0.25 * bottom});
  for (double f : {0.25, 0.5, 0.75}) {
    const double z = std::clamp(f * bottom, r, bottom - r);
    out.sphere_heights.push_back(z);
    out.porosity_spheres.push_back(
        measurement_sphere_porosity(sim.balls(), Vec3(0.5 * (x0 + x1), 0.5 * s.width, z), r)
            .porosity);
  }
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Stage 4's first part: the sleeper placed 1 mm above the bed, brought down to the
// preload and seated; what the cycles start from.
CycleLoop seat_sleeper(const BoxTestScene& s, Simulation& sim, BoxTestResult& out,
                       std::ostream* log) {
  CycleLoop loop;
  loop.x0 = 0.5 * (s.length - s.sleeper_length);
  loop.x1 = loop.x0 + s.sleeper_length;
  const double top = loop.top = bed_top(sim, loop.x0, loop.x1);
  // The sleeper: a rigid block over the full width, 1 mm above the bed.
  Wall sleeper;
  sleeper.name = "sleeper";
  sleeper.shape = WallShape::Box;
  sleeper.lo = Vec3(loop.x0, -0.05 * s.width, top + 1e-3);
  sleeper.hi = Vec3(loop.x1, 1.05 * s.width, top + 1e-3 + s.sleeper_height);
  sleeper.edge_radius = s.sleeper_edge_radius;
  sleeper.material = box_test::with_friction(s.wall, s.friction_loading);
  const Index wall = loop.wall = sim.add_wall(sleeper);
  Servo servo;
  servo.walls = {wall};
  servo.axis = -Vec3::UnitZ();
  const double preload = s.preload;
  servo.target_force = [preload](double) { return preload; };
  servo.max_speed = s.sleeper_max_speed;
  servo.gain = s.sleeper_gain;
  loop.servo = sim.add_servo(servo);
  measure_porosity(s, sim, loop.x0, loop.x1, top, out);
  if (log)
    *log << "stage 4: sleeper " << s.sleeper_length * 1e3 << " mm long on the bed at " << top * 1e3
         << " mm; grid porosity under it " << out.porosity_grid << " (interior "
         << out.porosity_grid_interior << ")\n";

  // Seat the sleeper: down to the bed until it carries the preload, then let the
  // bed come to equilibrium under it, with the seating's own local damping if the
  // scene gives one (a trial of docs/TRIALS.md).
  if (s.seating_local_damping) sim.set_local_damping(*s.seating_local_damping);
  sim.prepare();
  for (long k = 0;
       k < s.max_stage_steps && sim.servos()[loop.servo].measured_force < 0.95 * preload; ++k)
    sim.step();
  out.stages.push_back(settle(sim, "preload", s.equilibrium_ratio, s.max_stage_steps, log,
                              s.seating_creep_rule ? SettleRule::kSeated : SettleRule::kRatio,
                              [&sim, wall] { return -sim.walls()[wall].displacement.z(); }));
  if (s.seating_local_damping) sim.set_local_damping(s.sim.local_damping);
  if (log) {
    const SleeperBearing b = sleeper_bearing(sim, wall);
    // Placed 1 mm above the bed: what it went down beyond that is its seating's
    // settlement, the creep a bed that cannot rest under the preload shows.
    *log << "  sleeper bears on " << b.bodies << " particles (" << b.contacts
         << " contacts; force max " << b.max << " N, median " << b.p50 << " N); it went down "
         << -sim.walls()[wall].displacement.z() * 1e3 << " mm from 1 mm above the bed\n";
  }

  // Cycles: F(t) = (Fmin + Fmax)/2 − (Fmax − Fmin)/2·cos(2πf(t − t0)).
  loop.t0 = sim.time();
  sim.set_servo_target(loop.servo, sinusoidal_load(s.preload, s.peak_load, s.frequency, loop.t0));
  sim.reset_motion_reference();
  out.before = snapshot_contacts(sim, wall);
  out.near_before = count_near_pairs(sim, near_pair_gaps());
  out.position_start = sim.bodies().position;
  loop.z0 = sim.walls()[wall].displacement.z();
  const double period = 1.0 / s.frequency;
  loop.t_peak = loop.t0 + 0.5 * period;
  loop.t_end = loop.t0 + s.cycles * period;
  loop.step0 = sim.step_count();
  loop.energy0 = sim.energy();
  loop.cycles = CycleRecorder(s, sim, wall, loop.servo, loop.x0, loop.x1);
  return loop;
}

// One line on the cycle that just ended, for a run of many: where the settlement
// stands and when the run will end, at the rate of the cycles this process has run.
void log_cycle_progress(std::ostream& log, const BoxTestScene& s, const CycleRecords& records,
                        long cycles_this_process, double seconds_this_process) {
  const std::size_t n = records.count();
  const double per_cycle = seconds_this_process / static_cast<double>(cycles_this_process);
  const double rebound = records.settlement_peak[n - 1] - records.settlement_trough[n - 1];
  char line[200];
  std::snprintf(line, sizeof line,
                "  cycle %zu of %ld: permanent settlement %.4g mm, rebound %.4g mm; %.3g s a cycle",
                n, s.cycles, records.settlement_trough[n - 1] * 1e3, rebound * 1e3, per_cycle);
  log << line;
  if (static_cast<long>(n) < s.cycles)
    log << ", " << duration_text(per_cycle * static_cast<double>(s.cycles - static_cast<long>(n)))
        << " to go";
  log << '\n' << std::flush;
}

// Stage 4's cycles, from wherever `loop` stands (the start of loading, or a
// checkpoint: `resumed`), writing checkpoints as `plan` asks; then what the cycles
// measured. run_start: when this process started the run.
void run_cycles(const BoxTestScene& s, Simulation& sim, BoxTestResult& out, CycleLoop& loop,
                std::ostream* log, const CheckpointPlan& plan,
                const std::vector<ClumpTemplate>& templates, Clock::time_point run_start,
                bool resumed) {
  const Clock::time_point start = Clock::now();
  const double loop_before = loop.seconds, run_before = loop.run_seconds;
  Clock::time_point last_checkpoint = start, last_progress = start;
  const long done_at_start = loop.cycles.cycles_done();
  const auto checkpoint = [&] {
    CycleLoop at = loop;
    at.seconds = loop_before + seconds_since(start);
    at.run_seconds = run_before + seconds_since(run_start);
    // A checkpoint is insurance, not a result: one the file system refuses (a full
    // disk) is reported and the run goes on; the next interval tries again.
    try {
      write_checkpoint(plan, sim, out, at, templates);
    } catch (const std::runtime_error& e) {
      if (log) *log << "warning: " << e.what() << "; the run goes on without it\n";
    }
    last_checkpoint = Clock::now();
  };
  const bool checkpoints = !plan.path.empty();
  // A run killed during its first cycle resumes here, not from a new preparation.
  if (checkpoints && !resumed) checkpoint();
  const Index wall = loop.wall;
  while (sim.time() < loop.t_end) {
    sim.step();
    const Servo& sv = sim.servos()[loop.servo];
    const double err = sv.measured_force - sv.target_now;
    out.max_force_error = std::max(out.max_force_error, std::abs(err));
    loop.err2 += err * err;
    ++loop.samples;
    if (loop.cycles.sampling_series() && (sim.step_count() - loop.step0) % s.series_every == 0) {
      out.time.push_back(sim.time() - loop.t0);
      out.target_force.push_back(sv.target_now);
      out.sleeper_force.push_back(sv.measured_force);
      out.settlement.push_back(loop.z0 - sim.walls()[wall].displacement.z());
    }
    if (!loop.peak_done && sim.time() >= loop.t_peak) {
      loop.peak_done = true;
      out.at_peak = snapshot_contacts(sim, wall);
      out.position_peak = sim.bodies().position;
      loop.rotation_peak = sim.bodies().rotation;
      out.settlement_peak = loop.z0 - sim.walls()[wall].displacement.z();
    }
    const long done = loop.cycles.cycles_done();
    loop.cycles.after_step(sim, out.cycles);
    const bool cycle_ended = loop.cycles.cycles_done() != done;
    // A run of many cycles says how it goes about once a minute, and at its last cycle.
    if (cycle_ended && log && s.cycles > 1 &&
        (seconds_since(last_progress) >= kProgressSeconds || done + 1 == s.cycles)) {
      log_cycle_progress(*log, s, out.cycles, done + 1 - done_at_start, seconds_since(start));
      last_progress = Clock::now();
    }
    if (!checkpoints || sim.time() >= loop.t_end) continue;
    if ((cycle_ended && plan.every_cycles > 0 &&
         loop.cycles.cycles_done() % plan.every_cycles == 0) ||
        (plan.every_minutes > 0.0 && (sim.step_count() & 255) == 0 &&
         seconds_since(last_checkpoint) >= 60.0 * plan.every_minutes))
      checkpoint();
  }
  out.stages.push_back({"cycle", sim.step_count() - loop.step0, sim.time() - loop.t0,
                        loop_before + seconds_since(start), sim.unbalanced_force_ratio(), ""});
  out.stages.back().book_energy(loop.energy0, sim.energy());
  check_cycle_energy(sim, out.stages.back());
  out.rms_force_error = loop.samples ? std::sqrt(loop.err2 / loop.samples) : 0.0;
  out.after = snapshot_contacts(sim, wall);
  out.position_end = sim.bodies().position;
  const std::vector<Vec3> zero(sim.bodies().size(), Vec3::Zero());
  out.rotation_deg_loading = angles(loop.rotation_peak, zero);
  out.rotation_deg_unloading = angles(sim.bodies().rotation, loop.rotation_peak);
  out.rotation_deg_cycle = angles(sim.bodies().rotation, zero);
  out.rotation_loading = stats_of(out.rotation_deg_loading);
  out.rotation_unloading = stats_of(out.rotation_deg_unloading);
  out.rotation_cycle = stats_of(out.rotation_deg_cycle);
  out.max_displacement_peak = max_distance(out.position_peak, out.position_start);
  out.max_displacement_after = max_distance(out.position_end, out.position_start);
  out.permanent_settlement = loop.z0 - sim.walls()[wall].displacement.z();
  // The last cycle's rebound (the first's for one cycle).
  out.resilient_settlement = out.cycles.settlement_peak.back() - out.permanent_settlement;
  out.zones = measure_zones(out, loop.x0, loop.x1, loop.top, s.zone_depth);
  out.loaded = true;
  if (log)
    *log << "  cycle: settlement " << out.settlement_peak * 1e3 << " mm at peak, permanent "
         << out.permanent_settlement * 1e3 << " mm; force error max " << out.max_force_error
         << " N, rms " << out.rms_force_error << " N\n";
}

}  // namespace

void load_box_test(const BoxTestScene& s, Simulation& sim, BoxTestResult& out, std::ostream* log) {
  CycleLoop loop = seat_sleeper(s, sim, out, log);
  run_cycles(s, sim, out, loop, log, CheckpointPlan{}, {}, Clock::now(), false);
}

BoxTestResult run_box_test(const BoxTestScene& s, std::ostream* log,
                           const std::function<void(const Simulation&)>& at_end,
                           const CheckpointPlan& plan) {
  const Clock::time_point start = Clock::now();
  if (log && !s.numerics_preset.empty()) {
    *log << "numerics preset '" << s.numerics_preset << "' (docs/TRADEOFFS.md)";
    for (const std::string& field : s.preset_fields_kept) *log << "; the scene's own " << field;
    *log << "\n";
  }
  const bool resuming = plan.resume && !plan.path.empty() && std::filesystem::exists(plan.path);
  SimulationSettings quiet;
  quiet.log = log;
  PreparedBed bed{Simulation(quiet), {}, 0.0, {}};
  BoxTestResult out;
  Simulation& sim = bed.sim;
  double before = 0.0;  // wall seconds the run took before its last checkpoint
  // A checkpoint at every point between two preparation stages: insurance, not a
  // result, so one the file system refuses is reported and the run goes on.
  // The shared bed, when this run writes it, likewise: other runs prepare their own
  // without it.
  CheckpointPlan bed_plan = plan;
  bed_plan.path = plan.bed_path;
  bed_plan.scene_text = plan.bed_text;
  const bool writes_bed = plan.bed_writer && !plan.bed_path.empty();
  PrepCheckpoint at_point;
  if (!plan.path.empty() || writes_bed)
    at_point = [&](const PreparedBed& b, const PrepPoint& p) {
      PrepPoint now = p;
      now.run_seconds = before + seconds_since(start);
      const auto write = [&](const CheckpointPlan& to) {
        try {
          write_preparation_checkpoint(to, b, now);
        } catch (const std::runtime_error& e) {
          if (log) *log << "warning: " << e.what() << "; the run goes on without it\n";
        }
      };
      if (!plan.path.empty()) write(plan);
      if (writes_bed && p.done == PrepStage::kPrepared) write(bed_plan);
    };
  // Starts from the shared bed when there is one; one that cannot be read is reported
  // and this run prepares its own.
  const auto from_shared_bed = [&] {
    if (plan.bed_path.empty() || !std::filesystem::exists(plan.bed_path)) return false;
    try {
      RunCheckpoint c = read_checkpoint(bed_plan, sim);
      if (c.point.done != PrepStage::kPrepared)
        throw SetupError("checkpoint " + plan.bed_path + " holds no prepared bed");
      bed.templates = std::move(c.templates);
      bed.stages = std::move(c.stages);
      bed.dt_spheres = c.dt_spheres;
      before = c.point.run_seconds;  // the bed's preparation, as its writer ran it
      if (log)
        *log << c.log << "prepared bed from " << plan.bed_path
             << ": another run of the study prepared it from the same scene and seed\n";
      return true;
    } catch (const SetupError& e) {
      if (log) *log << "warning: " << e.what() << "; this run prepares its own bed\n";
      bed = PreparedBed{Simulation(quiet), {}, 0.0, {}};
      before = 0.0;
      return false;
    }
  };
  bool loading_resumed = false;
  if (resuming) {
    RunCheckpoint c = read_checkpoint(plan, sim);
    bed.templates = std::move(c.templates);
    if (c.point.done != PrepStage::kNone) {
      bed.stages = std::move(c.stages);
      bed.dt_spheres = c.dt_spheres;
      before = c.point.run_seconds;
      if (log)
        *log << c.log << "resumed from checkpoint " << plan.path << ": step " << sim.step_count()
             << ", in the preparation after its stage '"
             << (bed.stages.empty() ? std::string("import") : bed.stages.back().name) << "'\n";
      continue_box_test_preparation(s, bed, c.point, log, at_point);
    } else {
      loading_resumed = true;
      out = std::move(c.result);
      before = c.loop.run_seconds;
      sim.set_servo_target(c.loop.servo,
                           sinusoidal_load(s.preload, s.peak_load, s.frequency, c.loop.t0));
      if (log)
        *log << c.log << "resumed from checkpoint " << plan.path << ": step " << sim.step_count()
             << ", " << c.loop.cycles.cycles_done() << " of " << s.cycles << " cycles done\n";
      run_cycles(s, sim, out, c.loop, log, plan, bed.templates, start, true);
    }
  } else if (!from_shared_bed()) {
    bed = prepare_box_test(s, log, at_point);
  }
  if (!loading_resumed) {
    out.scene_name = s.name;
    out.stages = bed.stages;
    if (s.stop_after.empty()) {
      CycleLoop loop = seat_sleeper(s, sim, out, log);
      loop.run_seconds = before;
      run_cycles(s, sim, out, loop, log, plan, bed.templates, start, false);
    } else {
      const double x0 = 0.5 * (s.length - s.sleeper_length);
      measure_porosity(s, sim, x0, x0 + s.sleeper_length, bed_top(sim, x0, x0 + s.sleeper_length),
                       out);
      out.before = snapshot_contacts(sim);
      out.position_start = out.position_end = sim.bodies().position;
      out.rotation_deg_cycle =
          angles(sim.bodies().rotation, std::vector<Vec3>(sim.bodies().size(), Vec3::Zero()));
      out.rotation_cycle = stats_of(out.rotation_deg_cycle);
    }
  }
  out.bodies = sim.bodies().size();
  out.balls = sim.balls().size();
  out.dt = sim.dt();
  out.dt_critical = sim.critical_dt();
  out.energy = sim.energy();
  out.shape_index.resize(static_cast<std::size_t>(out.bodies));
  for (Index b = 0; b < out.bodies; ++b) out.shape_index[b] = b;
  if (s.clumps) {
    // Shapes are cheap beside a run (1,936 Sample 2 clumps generated and measured in
    // 10 s on one core: ballast clump --preset table2/sample2 --count 1936 --mass paper
    // --threads 1), so every archive carries them.
    ClumpSampleRecord c;
    c.shape = s.shape;
    c.params = *s.clumps;
    c.mass = {s.mass_mode, s.simulated_density(), s.mass_accuracy};
    c.seed = s.seed;
    c.templates = std::move(bed.templates);
    c.shapes = measure_clump_shapes(c.templates, virtual_sphere_radius(c.params), {});
    out.clumps = std::move(c);
  }
  out.wall_seconds = before + seconds_since(start);
  if (at_end) at_end(sim);
  return out;
}

}  // namespace ballast
