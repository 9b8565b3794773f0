// What --phase-times reports beyond the sums (engine/phase_times.hpp): the spread of
// the step's wall time and each thread's median phases. On a shared host a few steps
// in which a vCPU was taken away for milliseconds hold much of a run's time, and on
// two threads such a delay of either vCPU stalls both at the next synchronisation;
// the median step is what the code costs when the host delays neither.
#pragma once

#include <array>

#include "engine/phase_times.hpp"

namespace ballast {

struct PhaseStats {
  double step_mean_us = 0.0;
  std::array<double, 3> step_quartiles_us{};  // 25 %, median, 75 %
  // Σ max(0, step − median) / Σ step: the share of the run's time that its steps
  // spent beyond the median step's time.
  double time_beyond_median = 0.0;
  // Per thread, the median of each phase over the steps, µs, in PhaseTimes::Thread's
  // order: fork, contacts, barrier, walls and integrate, join.
  std::vector<std::array<double, 5>> thread_median_us;
};

PhaseStats phase_stats(const PhaseTimes& p);

}  // namespace ballast
