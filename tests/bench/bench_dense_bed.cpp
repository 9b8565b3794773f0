// Dense-bed throughput and the speed/accuracy trade, measured with Google Benchmark.
//
//   make bench      (or build/tests/bench/ballast_bench --benchmark_filter=DenseBed)
//
// DenseBed: the scene — 1,936 spheres of 36.25 mm settled in the
// 700 × 300 mm box, kn = ks = 5.08e9 N/m, mu = 0.5, gravity, PFC local damping —
// stepped on 1 and 2 threads. The counter ball_steps/s is the figure of merit;
// compare the two thread counts from one run (the machine is shared and noisy).
// The random_order:1 variants number the same bed's bodies at random, random_order:2
// at random and then by the engine's spatial sort (a packing file from another code,
// Simulation::sort_bodies_spatially); fast_path:0
// runs the general (clump-capable) path on the same spheres; ledger:0 keeps no
// energy ledger (SimulationSettings::energy_ledger), to show what it costs.
//
// EnergyDrift: what a larger timestep costs in accuracy. 300 undamped frictional
// spheres fall into the box at 10 g for 0.05 s; drift is |energy balance| over the
// energy released, for dt = safety × dt_critical.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>

#include "cases/bed.hpp"
#include "dense_bed.hpp"

using namespace ballast;

namespace {

void DenseBed(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  omp_set_num_threads(threads);
  Simulation sim = settled_dense_bed(static_cast<BedOrder>(state.range(1)), state.range(3) == 1);
  sim.set_sphere_fast_path(state.range(2) == 1);
  const long steps_per_iteration = 200;
  const long builds0 = sim.neighbour_builds();
  for (auto _ : state) sim.run(steps_per_iteration);
  state.counters["steps/build"] = double(steps_per_iteration) * state.iterations() /
                                  std::max(1L, sim.neighbour_builds() - builds0);
  const double ball_steps = double(sim.balls().size()) * steps_per_iteration * state.iterations();
  state.counters["ball_steps/s"] = benchmark::Counter(ball_steps, benchmark::Counter::kIsRate);
  state.counters["balls"] = sim.balls().size();
  state.counters["contacts/ball"] =
      double(sim.contacts().ball_contacts + sim.contacts().wall_contacts) / sim.balls().size();
  state.counters["dt_us"] = sim.dt() * 1e6;
  omp_set_num_threads(omp_get_num_procs());
}
// Second argument: 0 = bodies in spatial order (as the packings give them), 1 = the
// same bed with bodies numbered at random, to show what locality is worth, 2 = numbered
// at random and sorted by the engine, to show that the sort wins it back. Third:
// 1 = the sphere-only scene's fast path (the default), 0 = the general path, to
// show what that is worth (the two end in the same bits: test_determinism).
// Fourth: 1 = the energy ledger kept (as the box test keeps it), 0 = none.
BENCHMARK(DenseBed)
    ->Args({1, 0, 1, 1})
    ->Args({2, 0, 1, 1})
    ->Args({1, 1, 1, 1})
    ->Args({2, 1, 1, 1})
    ->Args({1, 2, 1, 1})
    ->Args({2, 2, 1, 1})
    ->Args({1, 0, 0, 1})
    ->Args({2, 0, 0, 1})
    ->Args({1, 0, 1, 0})
    ->Args({2, 0, 1, 0})
    ->ArgNames({"threads", "random_order", "fast_path", "ledger"})
    ->UseRealTime()
    ->MinTime(3.0)
    ->Unit(benchmark::kMillisecond);

void EnergyDrift(benchmark::State& state) {
  const double safety = state.range(0) / 100.0;
  double drift = 0.0;
  long balls = 0, steps = 0;
  for (auto _ : state) {
    BedOptions o;
    o.count = 300;
    o.friction = 0.5;
    o.sim.local_damping = 0.0;
    o.rubber_base = false;
    o.sim.gravity = Vec3(0, 0, -98.1);
    o.sim.dt_safety = safety;
    Simulation sim = make_bed(o);
    while (sim.time() < 0.05) sim.step();
    const EnergyBudget e = sim.energy();
    drift = std::abs(e.balance()) / e.gravity_work;
    balls = sim.balls().size();
    steps = sim.step_count();
  }
  state.counters["safety"] = safety;
  state.counters["drift_%"] = 100.0 * drift;
  state.counters["steps"] = double(steps);
  state.counters["ball_steps/s"] =
      benchmark::Counter(double(balls) * steps * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(EnergyDrift)
    ->Arg(80)
    ->Arg(40)
    ->Arg(20)
    ->Arg(10)
    ->ArgName("safety%")
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
