#include "cases/settling_demo.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "cases/bed.hpp"

namespace ballast {

namespace {

void print_header(std::ostream& out) {
  char line[200];
  std::snprintf(line, sizeof line, "%-10s %9s %9s %11s %8s %5s %9s %8s %9s %9s\n", "phase", "step",
                "t (s)", "KE (J)", "contacts", "Z", "Fmax (N)", "Fmean(N)", "unbal.", "E err");
  out << line;
}

void print_row(std::ostream& out, const char* phase, const Simulation& sim) {
  const ContactStats c = sim.contacts();
  const EnergyBudget e = sim.energy();
  const double scale = std::max(e.gravity_work, 1e-30);
  char line[200];
  std::snprintf(line, sizeof line, "%-10s %9ld %9.4f %11.4e %8ld %5.2f %9.1f %8.2f %9.2e %9.1e\n",
                phase, sim.step_count(), sim.time(), e.kinetic(), c.ball_contacts + c.wall_contacts,
                c.coordination, c.max_force, c.mean_force, sim.unbalanced_force_ratio(),
                std::abs(e.balance()) / scale);
  out << line << std::flush;
}

// Steps until `done` holds (checked every 500 steps, after a minimum time).
template <class Done>
void run_phase(Simulation& sim, const char* name, const SettlingDemoOptions& o, std::ostream& out,
               Done&& done) {
  const double t0 = sim.time();
  long k = 1;
  for (; k <= o.max_steps_per_phase; ++k) {
    sim.step();
    if (sim.time() - t0 >= o.min_phase_time && k % 500 == 0 && done()) break;
    if (k % o.report_every == 0) print_row(out, name, sim);
  }
  print_row(out, name, sim);  // the phase's last state, once
}

}  // namespace

SettlingDemoResult run_settling_demo(const SettlingDemoOptions& o, std::ostream& out) {
  BedOptions bed;
  bed.count = o.spheres;
  bed.seed = o.seed;
  bed.sim.dt_safety = o.dt_safety;
  bed.sim.gravity = Vec3(0.0, 0.0, -9.81 * o.gravity_factor);
  bed.sim.local_damping = 0.0;
  bed.sim.damping_ratio = o.pour_damping_ratio;
  bed.sim.log = &out;
  Simulation sim = make_bed(bed);
  out << "settling demo: " << o.spheres << " spheres of " << bed.diameter * 1e3 << " mm in the "
      << bed.length * 1e3 << " x " << bed.width * 1e3
      << " mm box on a rubber base (Lu & McDowell 2007, box test)\n";
  const auto start = std::chrono::steady_clock::now();
  sim.prepare();
  print_header(out);

  const auto at_rest = [&] {
    const EnergyBudget e = sim.energy();
    return e.kinetic() < 1e-3 * e.gravity_work;
  };
  const auto balanced = [&] { return sim.unbalanced_force_ratio() < o.target_ratio; };
  run_phase(sim, "pour", o, out, at_rest);
  sim.set_damping_ratio(0.0);
  sim.set_local_damping(0.7);
  run_phase(sim, "compact", o, out, balanced);
  sim.set_gravity(Vec3(0.0, 0.0, -9.81));
  run_phase(sim, "relax", o, out, balanced);
  sim.set_all_friction(box_test::kFrictionLoading);
  run_phase(sim, "mu=0.5", o, out, balanced);

  SettlingDemoResult r;
  r.steps = sim.step_count();
  r.time = sim.time();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.unbalanced_ratio = sim.unbalanced_force_ratio();
  for (Index k = 0; k < sim.balls().size(); ++k)
    r.bed_height = std::max(r.bed_height, sim.balls().position[k].z() + sim.balls().radius[k]);
  const ContactStats c = sim.contacts();
  r.contacts = c.ball_contacts + c.wall_contacts;
  const EnergyBudget e = sim.energy();
  r.energy_balance_error = std::abs(e.balance()) / std::max(e.gravity_work, 1e-30);

  out << "\nsettled: " << r.steps << " steps, " << r.time << " s simulated in " << r.wall_seconds
      << " s (" << sim.balls().size() * double(r.steps) / r.wall_seconds << " ball-steps/s)\n"
      << "bed height " << r.bed_height * 1e3 << " mm, " << c.ball_contacts << " ball-ball and "
      << c.wall_contacts << " ball-wall contacts, coordination " << c.coordination << ", max force "
      << c.max_force << " N, mean " << c.mean_force << " N\n"
      << "energy: gravity work " << e.gravity_work << " J = kinetic " << e.kinetic()
      << " + elastic " << e.elastic << " + friction " << e.friction_dissipated
      << " + local damping " << e.damping_dissipated << " + viscous " << e.viscous_dissipated
      << " J (balance error " << r.energy_balance_error * 100 << " %)\n";
  return r;
}

}  // namespace ballast
