// Which runs of a study one process does, and how: the shard (--shard K/N) and the
// split of the cores into runs side by side (--jobs) times threads per run
// (--threads). Pure functions, so that tests pin the choices.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "study/matrix/study_matrix.hpp"

namespace ballast {

// Shard K of N (1 <= K <= N): the runs whose index % N == K - 1. 1/1 is the whole study.
struct Shard {
  int index = 1;  // K
  int count = 1;  // N
  bool whole() const { return count == 1; }
  bool contains(std::size_t run_index) const {
    return run_index % static_cast<std::size_t>(count) == static_cast<std::size_t>(index - 1);
  }
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};

// "K/N" with 1 <= K <= N <= 100000; throws SetupError naming --shard, the value and
// what is allowed.
Shard parse_shard(const std::string& text);

// The runs of `spec` in `shard`, in study order.
std::vector<const RunSpec*> shard_runs(const StudySpec& spec, const Shard& shard);

struct Parallelism {
  int jobs = 1;     // runs side by side (outer OpenMP threads)
  int threads = 1;  // OpenMP threads inside each run
};

// Runs first, then threads: a run's engine scales sub-linearly (2.1x on 2 threads at
// best, docs/PERFORMANCE.md) while independent runs scale linearly. With neither given:
// jobs = min(runs, cores), threads = cores / jobs (2 cores, 3 runs: 2 x 1; 16 cores,
// 3 runs: 3 x 5). One given: the other from it, at least 1. Both given: as given.
// Never more jobs than runs. 0 means "not given". `cores` >= 1, `runs` >= 0.
Parallelism plan_parallelism(int cores, std::size_t runs, int jobs, int threads);

}  // namespace ballast
