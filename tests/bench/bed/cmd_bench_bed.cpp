#include "tests/bench/bed/cmd_bench_bed.hpp"

#include <omp.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cases/bench_bed.hpp"
#include "cases/packing_bodies.hpp"
#include "engine/errors.hpp"
#include "engine/sphere_kernel.hpp"
#include "engine/state_hash.hpp"
#include "tests/bench/bed/bench_bed_scaling.hpp"
#include "tests/bench/bed/phase_stats.hpp"

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
  bool scaling = false;
  long chunk = 500;
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
  const PhaseStats st = phase_stats(p);
  nlohmann::json medians = nlohmann::json::array();
  for (const std::array<double, 5>& m : st.thread_median_us)
    medians.push_back({{"fork_us", m[0]},
                       {"contacts_us", m[1]},
                       {"barrier_us", m[2]},
                       {"walls_and_integrate_us", m[3]},
                       {"join_us", m[4]}});
  return {{"steps", p.steps},
          {"serial_us", p.serial * k},
          {"threads", threads},
          {"step_us",
           {{"mean", st.step_mean_us},
            {"quartiles", st.step_quartiles_us},
            {"time_beyond_median", st.time_beyond_median}}},
          {"thread_medians", medians}};
}

nlohmann::json means_json(const ContactForceMeans& m) {
  return {{"count", m.count},
          {"mean_normal_force_N", m.normal},
          {"mean_tangential_force_N", m.tangential}};
}

std::string hex(unsigned long long h) {
  char s[32];
  std::snprintf(s, sizeof s, "%016llx", h);
  return s;
}

// --scaling: one thread against T in one process (tests/bench/bed/bench_bed_scaling.hpp).
void run_scaling(const BenchBedArgs& a, const Packing& packing) {
  const int threads = a.threads > 0 ? a.threads : omp_get_max_threads();
  if (threads < 2)
    throw SetupError("--threads = " + std::to_string(threads) +
                     ": --scaling compares one thread with this many (allowed: 2 or more)");
  if (a.phase_times || !a.export_packing.empty())
    throw SetupError(std::string(a.phase_times ? "--phase-times" : "--export-packing") +
                     " with --scaling: it steps several copies of the bed (allowed: a plain "
                     "bench-bed run for them)");
  const ScalingRun s = interleaved_scaling(packing, a.bed, a.steps, a.chunk, threads);
  const double ball_steps = double(packing.balls()) * double(a.steps);
  const bool same = s.bit_identical();
  const auto times_json = [](const TurnTimes& t) {
    return nlohmann::json{
        {"seconds", {t.seconds_one, t.seconds_many}},
        {"ratio", t.ratio()},
        {"per_turn_quartiles", {t.quantile(0.25), t.quantile(0.5), t.quantile(0.75)}}};
  };
  // null where /proc/stat could not be read or no busy tick (10 ms) passed in the turns.
  const auto share_json = [](const StealMeter& m) -> nlohmann::json {
    if (const auto v = m.share()) return *v;
    return nullptr;
  };
  nlohmann::json hashes = nlohmann::json::array();
  for (unsigned long long h : s.hash) hashes.push_back(hex(h));
  if (a.json) {
    const nlohmann::json j = {
        {"code", "ballast"},
        {"packing", a.packing},
        {"balls", packing.balls()},
        {"threads", threads},
        {"steps", a.steps},
        {"chunk_steps", a.chunk},
        {"turns", s.speedup.per_turn.size()},
        {"ball_steps_per_s",
         {ball_steps / s.speedup.seconds_one, ball_steps / s.speedup.seconds_many}},
        {"speedup", times_json(s.speedup)},
        {"independent_copies", times_json(s.independent)},
        {"host_steal_share",
         {{"one_thread", share_json(s.steal_one)},
          {"threads", share_json(s.steal_team)},
          {"independent_copies", share_json(s.steal_copies)}}},
        {"state_hash", hashes},
        {"bit_identical", same}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf(
        "%s: %ld steps in turns of %ld: 1 thread %.4g ball-steps/s, %d threads %.4g: speed-up "
        "%.3f (per turn: quartiles %.3f, %.3f, %.3f)\n",
        a.packing.c_str(), a.steps, a.chunk, ball_steps / s.speedup.seconds_one, threads,
        ball_steps / s.speedup.seconds_many, s.speedup.ratio(), s.speedup.quantile(0.25),
        s.speedup.quantile(0.5), s.speedup.quantile(0.75));
    std::printf(
        "the host's bound in the same turns, %d independent copies at once, one thread each: "
        "%.3f times one copy's throughput (per turn: quartiles %.3f, %.3f, %.3f)\n",
        threads, s.independent.ratio(), s.independent.quantile(0.25), s.independent.quantile(0.5),
        s.independent.quantile(0.75));
    const auto pct = [](const StealMeter& m) -> std::string {
      const auto v = m.share();
      if (!v) return "unknown";
      char text[32];
      std::snprintf(text, sizeof text, "%.1f %%", 100.0 * *v);
      return text;
    };
    std::printf(
        "the hypervisor's steal in the same turns (/proc/stat), share of the time the vCPUs "
        "wanted to run: 1 thread %s, %d threads %s, the copies %s\n",
        pct(s.steal_one).c_str(), threads, pct(s.steal_team).c_str(), pct(s.steal_copies).c_str());
    std::printf("state hashes (1 thread, %d threads, the copies): %s; %s\n", threads,
                hashes.dump().c_str(), same ? "bit-identical" : "NOT bit-identical");
  }
  if (!same) throw std::runtime_error("bench-bed --scaling: the copies' end states differ");
}

void run(BenchBedArgs& a) {
  a.bed.rotation = parse_rotation_integrator(a.rotation);
  a.bed.log = &std::cerr;
  const Packing packing = read_packing_file(a.packing);
  if (a.scaling) return run_scaling(a, packing);
  if (a.threads > 0) omp_set_num_threads(a.threads);
  Simulation sim = make_bench_bed(packing, a.bed);
  sim.prepare();  // neighbour search and timestep check: set-up, not timed
  sim.set_phase_timing(a.phase_times);
  const auto start = std::chrono::steady_clock::now();
  sim.run(a.steps);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const BenchBedPhysics p = measure_bench_bed(sim);
  const double rate = double(sim.balls().size()) * double(a.steps) / seconds;
  const std::string hash = hex(state_hash(sim));
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
                              {"keep_file_order", a.bed.keep_file_order},
                              {"energy_ledger", a.bed.energy_ledger},
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
      p.ball_ball.count, p.ball_wall.count, p.all.normal, p.all.tangential, p.kinetic(),
      hash.c_str());
  if (a.phase_times) {  // the JSON's figures, one line per thread
    const nlohmann::json t = phase_json(sim.phase_times());
    const auto print_threads = [](const nlohmann::json& threads) {
      for (std::size_t n = 0; n < threads.size(); ++n) {
        const nlohmann::json& u = threads[n];
        std::printf(
            "  thread %zu: fork %.2f, contacts %.2f, barrier %.2f, walls and integrate %.2f, "
            "join %.2f\n",
            n, u["fork_us"].get<double>(), u["contacts_us"].get<double>(),
            u["barrier_us"].get<double>(), u["walls_and_integrate_us"].get<double>(),
            u["join_us"].get<double>());
      }
    };
    std::printf("phase times, us per step: serial %.2f\n", t["serial_us"].get<double>());
    print_threads(t["threads"]);
    const nlohmann::json& st = t["step_us"];
    std::printf(
        "step, us: mean %.2f, quartiles %.2f, %.2f, %.2f; time beyond the median step: "
        "%.1f %% of the run\n",
        st["mean"].get<double>(), st["quartiles"][0].get<double>(),
        st["quartiles"][1].get<double>(), st["quartiles"][2].get<double>(),
        100.0 * st["time_beyond_median"].get<double>());
    std::printf("medians, us per step:\n");
    print_threads(t["thread_medians"]);
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
  cmd->add_flag("--keep-file-order", a->bed.keep_file_order,
                "keep the file's numbering of the bodies even where numbering them cell by "
                "cell pays (measures what the engine's spatial sort buys)");
  cmd->add_flag("--energy-ledger", a->bed.energy_ledger,
                "book every joule each step (gravity, damping, slip), as the box test does; "
                "measures what the ledger costs (off: kinetic energy only, as the peers)");
  cmd->add_option("--simd-lanes", a->bed.simd_lanes,
                  "SIMD lanes of a sphere bed's contact kernel: -1 the widest this CPU runs, 0 "
                  "none (one contact at a time), 4 AVX2, 8 AVX-512; the same bits")
      ->check(CLI::IsMember({-1, 0, 4, 8}));
  cmd->add_flag("--phase-times", a->phase_times,
                "report each thread's time per step in each phase of the step (fork, force "
                "pass, barrier, walls and integration, join) and the serial part, as means "
                "and as medians over the steps, and the spread of the step's wall time");
  cmd->add_flag("--scaling", a->scaling,
                "measure the speed-up from 1 thread to --threads (default: all cores) in one "
                "process: two copies of the bed take turns every --chunk steps, so that the "
                "host's drift falls on both; checks that their end states are bit-identical");
  cmd->add_option("--chunk", a->chunk, "steps per turn with --scaling")->check(CLI::PositiveNumber);
  cmd->add_option("--export-packing", a->export_packing,
                  "write the bed after the last step as a packing file");
  cmd->callback([a] { run(*a); });
}

}  // namespace ballast
