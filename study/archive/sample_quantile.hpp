// Quantiles of a sample, for the benchmark's reports (bench-bed --scaling's per-turn
// ratios, --phase-times' per-step times).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace ballast {

// Quantile q in [0, 1] of `v`, linear between order statistics (numpy's default);
// 0 for an empty sample.
template <class T>
double sample_quantile(std::vector<T> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double at = q * double(v.size() - 1);
  const std::size_t lo = std::size_t(std::floor(at));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return double(v[lo]) + (at - double(lo)) * (double(v[hi]) - double(v[lo]));
}

}  // namespace ballast
