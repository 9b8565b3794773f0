#include "study/cmd_bench_bed.hpp"

#include <omp.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cases/bench_bed.hpp"
#include "cases/packing_bodies.hpp"
#include "engine/sphere_kernel.hpp"
#include "engine/state_hash.hpp"

namespace ballast {

namespace {

struct BenchBedArgs {
  std::string packing;
  long steps = 1000;
  int threads = 0;
  bool json = false;
  std::string rotation = "full";
  std::string export_packing;
  bool phase_times = false;
  BenchBedOptions bed;
};

// Per thread, µs per step in each phase of the step (engine/phase_times.hpp).
nlohmann::json phase_json(const PhaseTimes& p) {
  const double k = p.steps > 0 ? 1e6 / double(p.steps) : 0.0;
  nlohmann::json threads = nlohmann::json::array();
  for (const PhaseTimes::Thread& t : p.thread)
    threads.push_back({{"fork_us", t.fork * k},
                       {"contacts_us", t.contacts * k},
                       {"barrier_us", t.barrier * k},
                       {"walls_and_integrate_us", t.integrate * k},
                       {"join_us", t.join * k}});
  return {{"steps", p.steps}, {"serial_us", p.serial * k}, {"threads", threads}};
}

nlohmann::json means_json(const ContactForceMeans& m) {
  return {{"count", m.count},
          {"mean_normal_force_N", m.normal},
          {"mean_tangential_force_N", m.tangential}};
}

void run(BenchBedArgs& a) {
  if (a.threads > 0) omp_set_num_threads(a.threads);
  a.bed.rotation = parse_rotation_integrator(a.rotation);
  a.bed.log = &std::cerr;
  const Packing packing = read_packing_file(a.packing);
  Simulation sim = make_bench_bed(packing, a.bed);
  sim.prepare();  // neighbour search and timestep check: set-up, not timed
  sim.set_phase_timing(a.phase_times);
  const auto start = std::chrono::steady_clock::now();
  sim.run(a.steps);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const BenchBedPhysics p = measure_bench_bed(sim);
  const double rate = double(sim.balls().size()) * double(a.steps) / seconds;
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx",
                static_cast<unsigned long long>(
                    state_hash(sim.bodies(), sim.ball_contacts(), sim.wall_contacts())));
  if (!a.export_packing.empty())
    write_packing_file(
        a.export_packing, packing_of(sim),
        "ballast bench-bed " + a.packing + " after " + std::to_string(a.steps) + " steps");
  if (a.json) {
    const nlohmann::json j = {{"code", "ballast"},
                              {"threads", omp_get_max_threads()},
                              {"processes", 1},
                              {"packing", a.packing},
                              {"bodies", sim.bodies().size()},
                              {"balls", sim.balls().size()},
                              {"clumps", packing.clumps},
                              {"steps", a.steps},
                              {"dt_s", sim.dt()},
                              {"dt_critical_estimate_s", sim.critical_dt()},
                              {"skin_m", sim.skin()},
                              {"neighbour_builds", sim.neighbour_builds()},
                              {"ball_ball_candidates", sim.ball_contacts().size()},
                              {"ball_wall_candidates", sim.wall_contacts().size()},
                              {"skip_far_candidates", a.bed.skip_far_candidates},
                              {"sphere_kernel", sphere_kernel_name(sim.sphere_kernel_lanes())},
                              {"rotation", a.rotation},
                              {"seconds", seconds},
                              {"ball_steps_per_s", rate},
                              {"ball_ball", means_json(p.ball_ball)},
                              {"ball_wall", means_json(p.ball_wall)},
                              {"all", means_json(p.all)},
                              {"kinetic_energy_J", p.kinetic()},
                              {"kinetic_translational_J", p.kinetic_translational},
                              {"kinetic_rotational_J", p.kinetic_rotational},
                              {"state_hash", hash}};
    nlohmann::json out = j;
    if (a.phase_times) out["phase_times"] = phase_json(sim.phase_times());
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf(
      "%s: %d bodies, %d balls, %ld steps of %g s on %d thread(s) in %.3f s: %.4g "
      "ball-steps/s\n",
      a.packing.c_str(), sim.bodies().size(), sim.balls().size(), a.steps, sim.dt(),
      omp_get_max_threads(), seconds, rate);
  std::printf(
      "contacts: %ld ball-ball, %ld ball-wall; mean normal %.6g N, mean tangential %.6g "
      "N; kinetic energy %.6g J; state hash %s\n",
      p.ball_ball.count, p.ball_wall.count, p.all.normal, p.all.tangential, p.kinetic(), hash);
  if (a.phase_times) {  // the JSON's figures, one line per thread
    const nlohmann::json t = phase_json(sim.phase_times());
    std::printf("phase times, us per step: serial %.2f\n", t["serial_us"].get<double>());
    for (std::size_t n = 0; n < t["threads"].size(); ++n) {
      const nlohmann::json& u = t["threads"][n];
      std::printf(
          "  thread %zu: fork %.2f, contacts %.2f, barrier %.2f, walls and integrate %.2f, "
          "join %.2f\n",
          n, u["fork_us"].get<double>(), u["contacts_us"].get<double>(),
          u["barrier_us"].get<double>(), u["walls_and_integrate_us"].get<double>(),
          u["join_us"].get<double>());
    }
  }
}

}  // namespace

void register_bench_bed_command(CLI::App& app) {
  auto a = std::make_shared<BenchBedArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bench-bed",
      "Step a packing in the box with the peer benchmark's physics (issue 7) and "
      "report ball-steps/s and the physics after N steps");
  cmd->add_option("packing", a->packing, "packing file (x y z r, or body x y z r)")->required();
  cmd->add_option("--steps", a->steps, "time steps to run and time")->check(CLI::PositiveNumber);
  cmd->add_option("--threads", a->threads, "OpenMP threads (0: OMP_NUM_THREADS or all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", a->json, "print the result as JSON");
  cmd->add_option("--rotation", a->rotation, "clump rotation integrator")
      ->check(CLI::IsMember({"pfc", "full"}));
  cmd->add_option("--stiffness", a->bed.contact_stiffness, "kn = ks per contact, N/m")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--friction", a->bed.friction, "Coulomb friction coefficient")
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--dt", a->bed.dt, "fixed time step, s")->check(CLI::PositiveNumber);
  cmd->add_option("--density", a->bed.density, "ball density, kg/m^3")->check(CLI::PositiveNumber);
  cmd->add_option("--local-damping", a->bed.local_damping,
                  "PFC local damping alpha (0 in the benchmark; the convention checks settle "
                  "with it)")
      ->check(CLI::Range(0.0, 0.99));
  cmd->add_flag("!--test-all-candidates", a->bed.skip_far_candidates,
                "evaluate every neighbour candidate each step, also those that cannot touch "
                "(the same bits; measures what skipping them saves)");
  cmd->add_option("--simd-lanes", a->bed.simd_lanes,
                  "SIMD lanes of a sphere bed's contact kernel: -1 the widest this CPU runs, 0 "
                  "none (one contact at a time), 4 AVX2, 8 AVX-512; the same bits")
      ->check(CLI::IsMember({-1, 0, 4, 8}));
  cmd->add_flag("--phase-times", a->phase_times,
                "report each thread's time per step in each phase of the step (fork, force "
                "pass, barrier, walls and integration, join) and the serial part");
  cmd->add_option("--export-packing", a->export_packing,
                  "write the bed after the last step as a packing file");
  cmd->callback([a] { run(*a); });
}

}  // namespace ballast
