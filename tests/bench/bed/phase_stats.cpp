#include "tests/bench/bed/phase_stats.hpp"

#include <algorithm>

#include "study/archive/sample_quantile.hpp"

namespace ballast {

PhaseStats phase_stats(const PhaseTimes& p) {
  PhaseStats s;
  const std::vector<float>& steps = p.step_seconds;
  if (!steps.empty()) {
    double total = 0.0;
    for (float t : steps) total += t;
    s.step_mean_us = 1e6 * total / double(steps.size());
    for (int k = 0; k < 3; ++k)
      s.step_quartiles_us[k] = 1e6 * sample_quantile(steps, 0.25 * (k + 1));
    const double median = s.step_quartiles_us[1] * 1e-6;
    double beyond = 0.0;
    for (float t : steps) beyond += std::max(0.0, double(t) - median);
    s.time_beyond_median = total > 0.0 ? beyond / total : 0.0;
  }
  for (const PhaseTimes::Thread& t : p.thread) {
    std::array<double, 5> median{};
    std::vector<float> phase(t.per_step.size());
    for (int k = 0; k < 5; ++k) {
      for (std::size_t n = 0; n < t.per_step.size(); ++n) phase[n] = t.per_step[n][k];
      median[k] = 1e6 * sample_quantile(phase, 0.5);
    }
    s.thread_median_us.push_back(median);
  }
  return s;
}

}  // namespace ballast
