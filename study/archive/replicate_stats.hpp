// Statistics over replicates (runs of one sample with different seeds): the unit of
// a physical claim. The same formulas as scripts/replicates.py, which the figures
// and compare.py use; the study summary prints these.
#pragma once

#include <cmath>
#include <vector>

namespace ballast {

// The 0.975 quantile of Student's t with `df` degrees of freedom: the factor of a
// two-sided 95 % confidence interval of a mean of df + 1 values. Tabulated to 30;
// beyond, the normal's 1.96 (t at 30 is 2.042, so the error is under 4 %).
inline double t_975(long df) {
  static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306,
                                 2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120,
                                 2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
                                 2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
  if (df < 1) return NAN;
  return df <= 30 ? table[df - 1] : 1.96;
}

struct ReplicateStats {
  long n = 0;
  double mean = 0.0;
  double sd = 0.0;          // sample standard deviation (n − 1); 0 for n = 1
  double half_width = NAN;  // of the 95 % interval of the mean; NaN for n < 2
};

inline ReplicateStats replicate_stats(const std::vector<double>& v) {
  ReplicateStats s;
  s.n = static_cast<long>(v.size());
  if (s.n == 0) return s;
  for (double x : v) s.mean += x;
  s.mean /= double(s.n);
  if (s.n < 2) return s;
  double ss = 0.0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(ss / double(s.n - 1));
  s.half_width = t_975(s.n - 1) * s.sd / std::sqrt(double(s.n));
  return s;
}

}  // namespace ballast
