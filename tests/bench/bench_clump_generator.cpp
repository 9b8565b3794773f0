// Clump generation speed (docs/PERFORMANCE.md, "Clump generation"). The target of
// issue 3: 10,000 Table 2 Sample 2 clumps with uniform-density mass properties at
// 0.5% accuracy in under 10 s on 2 cores. No main() here: ballast_bench's main comes
// with the other benchmark source (or benchmark::benchmark_main).
#include <benchmark/benchmark.h>
#include <omp.h>

#include "cases/clump_presets.hpp"
#include "engine/ball_union_integral.hpp"
#include "engine/clump_batch.hpp"
#include "engine/clump_generator.hpp"

namespace ballast {
namespace {

// The whole sample: geometry, union integration, principal frame. Arg: threads.
void BM_ClumpSampleTable2Sample2Uniform(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const ClumpParams q = load_clump_preset("table2/sample2").params;
  ClumpMassOptions mass;
  mass.mode = MassMode::kUniform;
  mass.accuracy = 0.005;
  const std::size_t count = 10000;
  omp_set_num_threads(threads);
  double balls = 0.0;
  for (auto _ : state) {
    const std::vector<ClumpTemplate> clumps = generate_clump_templates(q, mass, count, 1);
    balls = 0.0;
    for (const ClumpTemplate& t : clumps) balls += t.ball_count();
    benchmark::DoNotOptimize(clumps.data());
  }
  state.counters["threads"] = threads;
  state.counters["balls_per_clump"] = balls / count;
  state.counters["clumps_per_s"] =
      benchmark::Counter(static_cast<double>(count), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ClumpSampleTable2Sample2Uniform)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

// One clump's union integration at a given accuracy (Arg: accuracy in 1e-4 units),
// cycling through 256 Table 2 Sample 2 geometries; reports column evaluations.
void BM_UnionIntegralOneClump(benchmark::State& state) {
  const double accuracy = static_cast<double>(state.range(0)) * 1e-4;
  const ClumpParams q = load_clump_preset("table2/sample2").params;
  std::vector<ClumpGeometry> shapes;
  for (int i = 0; i < 256; ++i) {
    std::mt19937_64 rng = clump_rng(1, i);
    shapes.push_back(generate_clump(q, rng));
  }
  std::size_t k = 0;
  double evaluations = 0.0;
  for (auto _ : state) {
    const ClumpGeometry& g = shapes[k++ % shapes.size()];
    const BallUnionMoments u = integrate_ball_union(g.centres, g.radii, accuracy);
    evaluations += static_cast<double>(u.evaluations);
    benchmark::DoNotOptimize(u.volume);
  }
  state.counters["columns_per_clump"] =
      benchmark::Counter(evaluations, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_UnionIntegralOneClump)
    ->Arg(200)
    ->Arg(100)
    ->Arg(50)
    ->Arg(20)
    ->Unit(benchmark::kMicrosecond);

// Geometry alone (eqs 1-9 and the edges), for comparison.
void BM_GenerateClumpGeometry(benchmark::State& state) {
  const ClumpParams q = load_clump_preset("table2/sample2").params;
  std::uint64_t i = 0;
  for (auto _ : state) {
    std::mt19937_64 rng = clump_rng(1, i++);
    benchmark::DoNotOptimize(generate_clump(q, rng).radii.data());
  }
}
BENCHMARK(BM_GenerateClumpGeometry)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace ballast
