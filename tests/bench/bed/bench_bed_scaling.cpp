#include "tests/bench/bed/bench_bed_scaling.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>

#include "engine/state_hash.hpp"
#include "study/archive/sample_quantile.hpp"

namespace ballast {

void TurnTimes::add(double one, double many) {
  seconds_one += one;
  seconds_many += many;
  per_turn.push_back(one / many);
}

double TurnTimes::quantile(double q) const {
  return sample_quantile(per_turn, q);
}

bool ScalingRun::bit_identical() const {
  return !hash.empty() && std::all_of(hash.begin(), hash.end(),
                                      [this](unsigned long long h) { return h == hash[0]; });
}

namespace {

template <class Work>
double seconds_of(const Work& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

ScalingRun interleaved_scaling(const Packing& packing, const BenchBedOptions& options, long steps,
                               long chunk, int threads) {
  ScalingRun out;
  out.threads = threads;
  out.steps = steps;
  out.chunk = chunk;
  // Copy 0 on one thread, copy 1 on T threads, copies 2 .. T+1 at once, one thread
  // each; all built alike.
  std::vector<Simulation> sims;
  sims.reserve(std::size_t(threads) + 2);
  for (int c = 0; c < threads + 2; ++c) sims.push_back(make_bench_bed(packing, options));
  for (int c = 0; c < threads + 2; ++c) {
    omp_set_num_threads(c == 1 ? threads : 1);
    sims[std::size_t(c)].prepare();  // neighbour search and timestep check: set-up, not timed
  }
  // The three ways to step, each for n steps, returning its wall time; the steal
  // counters are read outside the timed part.
  const auto metered = [](StealMeter& meter, const auto& work) {
    meter.begin();
    const double seconds = seconds_of(work);
    meter.end();
    return seconds;
  };
  const auto one = [&](long n) {
    omp_set_num_threads(1);
    return metered(out.steal_one, [&] { sims[0].run(n); });
  };
  const auto team = [&](long n) {
    omp_set_num_threads(threads);
    return metered(out.steal_team, [&] { sims[1].run(n); });
  };
  const auto copies = [&](long n) {
    return metered(out.steal_copies, [&] {
#pragma omp parallel num_threads(threads)
      {
        // Each copy's steps open their own region, of one thread (the study's jobs
        // do the same, study_runner.cpp).
        omp_set_num_threads(1);
        sims[std::size_t(2 + omp_get_thread_num())].run(n);
      }
    });
  };
  for (long done = 0, k = 0; done < steps; done += chunk, ++k) {
    const long n = std::min(chunk, steps - done);
    double t_one, t_team, t_copies;
    if (k % 2 == 0) {  // forwards, then backwards: a linear drift cancels
      t_one = one(n), t_team = team(n), t_copies = copies(n);
    } else {
      t_copies = copies(n), t_team = team(n), t_one = one(n);
    }
    out.speedup.add(t_one, t_team);
    out.independent.add(t_one, t_copies / double(threads));
  }
  omp_set_num_threads(threads);
  for (const Simulation& s : sims) out.hash.push_back(state_hash(s));
  return out;
}

}  // namespace ballast
