#include "study/cli/cmd_demo.hpp"

#include <omp.h>

#include <iostream>
#include <memory>

#include "cases/settling_demo.hpp"

namespace ballast {

void register_demo_command(CLI::App& app) {
  auto opts = std::make_shared<SettlingDemoOptions>();
  auto threads = std::make_shared<int>(0);
  CLI::App* cmd =
      app.add_subcommand("demo", "Pour spheres into the box test's box and settle them");
  cmd->add_option("--spheres", opts->spheres, "number of 36.25 mm spheres")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--seed", opts->seed, "seed of the initial jitter");
  cmd->add_option("--gravity-factor", opts->gravity_factor, "enhanced gravity during compaction")
      ->check(CLI::Range(1.0, 1000.0));
  cmd->add_option("--target-ratio", opts->target_ratio, "unbalanced-force ratio ending a phase")
      ->check(CLI::Range(1e-6, 1.0));
  cmd->add_option("--max-steps", opts->max_steps_per_phase, "step limit per phase")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--report-every", opts->report_every, "steps between table rows")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--dt-safety", opts->dt_safety, "timestep as a fraction of the critical estimate")
      ->check(CLI::Range(1e-3, 1.0));
  cmd->add_option("--threads", *threads, "OpenMP threads (0: OMP_NUM_THREADS or all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->callback([opts, threads] {
    if (*threads > 0) omp_set_num_threads(*threads);
    std::cout << "threads: " << omp_get_max_threads() << "\n";
    run_settling_demo(*opts, std::cout);
  });
}

}  // namespace ballast
