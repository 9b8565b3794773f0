// Clump-bed throughput: about 1,770 Table 2 Sample 1 clumps (about 17,600 balls)
// poured into the 700 × 300 mm box, stepped on 1 and 2 threads with each rotation
// integrator. Compare ball_steps/s with DenseBed (spheres) from the same run: the
// target is a clump-bed ball-step costing no more than 1.5× a sphere-bed one.
//
//   build/tests/bench/ballast_bench --benchmark_filter='DenseBed|ClumpBed'
#include <benchmark/benchmark.h>
#include <omp.h>

#include <chrono>
#include <cstdio>

#include "cases/bed.hpp"

using namespace ballast;

namespace {

Simulation pour_clump_bed() {
  const auto start = std::chrono::steady_clock::now();
  BedOptions o;
  o.count = 1770;  // the paper's Sample 1 count
  o.clumps = ClumpParams{};  // Table 2 Sample 1
  o.mass.mode = MassMode::kUniform;
  o.friction = 0.5;
  o.rubber_base = false;
  // Fast pour as for the sphere bed: 20 g, dashpots, no local damping.
  o.gravity = Vec3(0, 0, -9.81 * 20);
  o.local_damping = 0.0;
  o.damping_ratio = 0.5;
  Simulation sim = make_bed(o);
  while (sim.time() < 0.2) sim.step();
  sim.set_gravity(Vec3(0, 0, -9.81));
  sim.set_damping_ratio(0.0);
  sim.set_local_damping(0.7);
  sim.run(3000);
  std::fprintf(stderr, "clump bed: %ld balls poured in %.0f s (%ld steps)\n",
               long(sim.balls().size()),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
               sim.step_count());
  return sim;
}

const Simulation& settled_clump_bed() {
  static const Simulation bed = pour_clump_bed();
  return bed;
}

void ClumpBed(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  omp_set_num_threads(threads);
  Simulation sim = settled_clump_bed();
  const long steps_per_iteration = 100;
  for (auto _ : state) sim.run(steps_per_iteration);
  const double ball_steps = double(sim.balls().size()) * steps_per_iteration * state.iterations();
  state.counters["ball_steps/s"] = benchmark::Counter(ball_steps, benchmark::Counter::kIsRate);
  state.counters["balls"] = sim.balls().size();
  state.counters["bodies"] = sim.bodies().size();
  state.counters["contacts/ball"] =
      double(sim.contacts().ball_contacts + sim.contacts().wall_contacts) / sim.balls().size();
  state.counters["dt_us"] = sim.dt() * 1e6;
  omp_set_num_threads(omp_get_num_procs());
}
BENCHMARK(ClumpBed)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->UseRealTime()
    ->MinTime(3.0)
    ->Unit(benchmark::kMillisecond);

}  // namespace
