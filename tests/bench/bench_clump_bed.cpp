// Clump-bed throughput: 1,936 Table 2 Sample 1 clumps (about 19,000 balls; the
// paper's sample has 1,770 and 17,642) in the 700 × 300 mm box, stepped on 1 and 2
// threads with each rotation integrator. Compare ball_steps/s with DenseBed (spheres) from the same
// run: the target is a clump-bed ball-step costing no more than 1.5× a sphere-bed one.
//
//   build/tests/bench/ballast_bench --benchmark_filter='DenseBed|ClumpBed'
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "cases/bed.hpp"
#include "dense_bed.hpp"
#include "engine/cell_list.hpp"

using namespace ballast;

namespace {

// Pouring 17,600 balls from a loose cloud takes many minutes at a clump's timestep.
// Instead: the settled sphere bed of DenseBed, each sphere replaced by a Table 2
// Sample 1 clump generated inside it (virtual-sphere factor 1, so no two clumps
// overlap), then 0.025 s at 100 g and 0.01 s at 20 g with dashpots to close the gaps into contacts,
// then the benchmark conditions.
Simulation pour_clump_bed() {
  const auto start = std::chrono::steady_clock::now();
  const Simulation& spheres = settled_dense_bed(BedOrder::kSpatial);
  BedOptions o;
  o.count = static_cast<int>(spheres.bodies().size());
  o.centres = spheres.bodies().position;
  o.clumps = ClumpParams{};  // Table 2 Sample 1
  o.clumps->virtual_sphere_factor = 1.0;
  o.mass.mode = MassMode::kPaper;
  o.friction = 0.5;
  o.rubber_base = false;
  o.sim.gravity = Vec3(0, 0, -9.81 * 100);
  o.sim.local_damping = 0.0;
  o.sim.damping_ratio = 0.5;
  Simulation sim = make_bed(o);
  while (sim.time() < 0.025) sim.step();
  sim.set_gravity(Vec3(0, 0, -9.81 * 20));
  while (sim.time() < 0.035) sim.step();
  sim.set_gravity(Vec3(0, 0, -9.81));
  sim.set_damping_ratio(0.0);
  sim.set_local_damping(0.7);
  sim.run(3000);
  std::fprintf(stderr, "clump bed: %ld balls in %ld clumps settled in %.0f s (%ld steps)\n",
               long(sim.balls().size()), long(sim.bodies().size()),
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
  const bool full = state.range(1) == 1;
  if (full) sim.set_rotation_integrator(RotationIntegrator::kFull);
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
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Args({2, 1})
    ->ArgNames({"threads", "full_rotation"})
    ->UseRealTime()
    ->MinTime(3.0)
    ->Unit(benchmark::kMillisecond);

// The neighbour search a build runs (cell list, then candidate pairs within
// r_a + r_b + skin) on the same settled clump bed: most of a build's cost, which
// RebuildPolicy (engine/rebuild_policy.hpp) weighs against the live candidates an
// early build saves. Compare ms per build with the step of ClumpBed in the same run.
void NeighbourSearch(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  omp_set_num_threads(threads);
  const Simulation& sim = settled_clump_bed();
  const BallStore& balls = sim.balls();
  double max_radius = 0.0;
  for (double r : balls.radius) max_radius = std::max(max_radius, r);
  CellList cells;
  std::vector<Index> a, b;
  for (auto _ : state) {
    cells.build(balls.position, sim.settings().domain_lo, sim.settings().domain_hi,
                2.0 * max_radius + sim.skin());
    find_candidate_pairs(cells, balls.position, balls.radius, balls.body, sim.skin(), a, b);
    benchmark::DoNotOptimize(a.data());
  }
  state.counters["balls"] = balls.size();
  state.counters["candidates"] = double(a.size());
  omp_set_num_threads(omp_get_num_procs());
}
BENCHMARK(NeighbourSearch)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->UseRealTime()
    ->MinTime(2.0)
    ->Unit(benchmark::kMillisecond);

}  // namespace
