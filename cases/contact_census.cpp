#include "cases/contact_census.hpp"

#include <algorithm>
#include <cmath>

namespace ballast {

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double at = q * double(values.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (at - double(lo)) * (values[hi] - values[lo]);
}

SleeperBearing sleeper_bearing(const Simulation& sim, Index sleeper) {
  SleeperBearing s;
  const ContactList& c = sim.wall_contacts();
  std::vector<double> forces;
  std::vector<Index> bodies;
  for (Index k = 0; k < c.size(); ++k) {
    if (!c.active[k] || c.b[k] != sleeper) continue;
    forces.push_back(c.force(k).norm());
    bodies.push_back(sim.balls().body[c.a[k]]);
  }
  std::sort(bodies.begin(), bodies.end());
  s.contacts = static_cast<long>(forces.size());
  s.bodies = std::unique(bodies.begin(), bodies.end()) - bodies.begin();
  for (double f : forces) {
    s.total += f;
    s.max = std::max(s.max, f);
  }
  s.p50 = percentile(forces, 0.5);
  s.p90 = percentile(forces, 0.9);
  return s;
}

ContactSnapshot snapshot_contacts(const Simulation& sim, std::optional<Index> sleeper) {
  ContactSnapshot s;
  s.stats = sim.contacts();
  const ContactList& c = sim.ball_contacts();
  const BallStore& b = sim.balls();
  for (Index k = 0; k < c.size(); ++k) {
    if (!c.active[k]) continue;
    s.from.push_back(b.position[c.a[k]]);
    s.to.push_back(b.position[c.b[k]]);
    s.force.push_back(c.force(k).norm());
  }
  s.force_p50 = percentile(s.force, 0.5);
  s.force_p90 = percentile(s.force, 0.9);
  s.force_p99 = percentile(s.force, 0.99);
  if (sleeper) s.sleeper = sleeper_bearing(sim, *sleeper);
  return s;
}

std::vector<double> near_pair_gaps() {
  return {0.0, 1e-4, 5e-4, 1e-3, 2e-3, 5e-3, 9e-3};
}

NearPairs count_near_pairs(const Simulation& sim, const std::vector<double>& gaps) {
  NearPairs out;
  out.gap = gaps;
  out.ball_pairs.assign(gaps.size(), 0);
  out.wall_pairs.assign(gaps.size(), 0);
  const BallStore& b = sim.balls();
  const Index n = b.size();
  if (n == 0 || gaps.empty()) return out;
  double r_max = 0.0;
  for (double r : b.radius) r_max = std::max(r_max, r);
  const double reach = 2.0 * r_max + gaps.back();
  // The gap band a distance d falls in: the first tolerance it satisfies.
  const auto count_gap = [&gaps](double gap, std::vector<long>& into) {
    const auto it = std::lower_bound(gaps.begin(), gaps.end(), gap);
    // gap <= gaps[i] for every i from it on; a touching pair (gap < 0) counts at 0 too.
    for (auto k = static_cast<std::size_t>(it - gaps.begin()); k < gaps.size(); ++k) ++into[k];
  };
  // A grid of cells of side `reach` over the balls' bounding box: a pair within
  // reach lies in the same or a neighbouring cell.
  Vec3 lo = b.position[0], hi = b.position[0];
  for (const Vec3& x : b.position) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  long dim[3];
  for (int a = 0; a < 3; ++a) dim[a] = long((hi[a] - lo[a]) / reach) + 1;
  const auto cell_of = [&](const Vec3& x, int a) { return long((x[a] - lo[a]) / reach); };
  std::vector<std::vector<Index>> cells(static_cast<std::size_t>(dim[0] * dim[1] * dim[2]));
  const auto flat = [&dim](long i, long j, long k) { return i + dim[0] * (j + dim[1] * k); };
  for (Index i = 0; i < n; ++i)
    cells[flat(cell_of(b.position[i], 0), cell_of(b.position[i], 1), cell_of(b.position[i], 2))]
        .push_back(i);
  for (Index i = 0; i < n; ++i) {
    const long ci = cell_of(b.position[i], 0), cj = cell_of(b.position[i], 1),
               ck = cell_of(b.position[i], 2);
    for (long k = std::max(0L, ck - 1); k <= std::min(dim[2] - 1, ck + 1); ++k)
      for (long j = std::max(0L, cj - 1); j <= std::min(dim[1] - 1, cj + 1); ++j)
        for (long c = std::max(0L, ci - 1); c <= std::min(dim[0] - 1, ci + 1); ++c)
          for (Index m : cells[flat(c, j, k)]) {
            if (m <= i || b.body[m] == b.body[i]) continue;
            const double gap = (b.position[i] - b.position[m]).norm() - b.radius[i] - b.radius[m];
            count_gap(gap, out.ball_pairs);
          }
  }
  // Within a clump: every pair of its balls (a clump is small and contiguous).
  for (Index i = 0; i < n; ++i)
    for (Index j = i + 1; j < n && b.body[j] == b.body[i]; ++j)
      if ((b.position[i] - b.position[j]).norm() < b.radius[i] + b.radius[j])
        ++out.intra_clump_pairs;
  for (Index i = 0; i < n; ++i)
    for (const Wall& w : sim.walls()) {
      const WallTouch t = touch_wall(w, b.position[i], b.radius[i]);
      count_gap(-t.overlap, out.wall_pairs);
    }
  return out;
}

}  // namespace ballast
