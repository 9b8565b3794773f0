#include "engine/ball_union_integral.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <sstream>

#include "engine/errors.hpp"

namespace ballast {
namespace {

// A ball relative to the reference point, with its squared radius.
struct Ball {
  double x, y, z, r, r2;
};

// Integrals along one vertical line through the union: ∫dz, ∫z dz, ∫z² dz.
struct Column {
  double len = 0.0, z1 = 0.0, z2 = 0.0;
};

// V, first moments, second moments ∫x_i x_j dV, about the reference point.
enum Moment { kV, kSx, kSy, kSz, kSxx, kSyy, kSzz, kSxy, kSxz, kSyz, kMomentCount };
using Moments = std::array<double, kMomentCount>;

// A leaf of the quadtree over (x, y): a square of half-size s centred at (x, y).
struct Cell {
  double x, y, s;
  int cand_begin, cand_count;  // balls whose disk meets the square, in the pool
  std::array<Column, 4> sub;   // columns at the centres of the four quarters
  Moments fine;                // 2x2 midpoint rule
  double err_v, err_i;         // error estimates of `fine` for V and ‖I‖_2
};

// Midpoint-rule moments of a square of area a, half-size s, whose column at its
// centre (x, y) is col. ∫x² over the square = a·(x² + s²/3).
Moments column_moments(const Column& col, double x, double y, double s, double a) {
  const double w = s * s / 3.0;
  return {a * col.len,   a * x * col.len,           a * y * col.len,
          a * col.z1,    a * (x * x + w) * col.len, a * (y * y + w) * col.len,
          a * col.z2,    a * x * y * col.len,       a * x * col.z1,
          a * y * col.z1};
}

Mat3 second_moment_matrix(const Moments& m);

// Spectral norm of the unit-density inertia tensor tr(M)𝟙 - M built from the second
// moments of d: by Weyl's inequality it bounds how far d can move any principal moment.
double inertia_norm(const Moments& d) {
  const Mat3 m2 = second_moment_matrix(d);
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(m2.trace() * Mat3::Identity() - m2, Eigen::EigenvaluesOnly);
  return eig.eigenvalues().cwiseAbs().maxCoeff();
}

Mat3 second_moment_matrix(const Moments& m) {
  Mat3 s;
  s << m[kSxx], m[kSxy], m[kSxz], m[kSxy], m[kSyy], m[kSyz], m[kSxz], m[kSyz], m[kSzz];
  return s;
}

// Length of [lo, hi] not covered by the sorted intervals `cover`.
double uncovered_length(double lo, double hi, const std::vector<std::pair<double, double>>& cover) {
  double open = 0.0, from = lo;
  for (const auto& [a, b] : cover) {
    if (a >= hi) break;
    if (b <= from) continue;
    if (a > from) open += a - from;
    from = std::max(from, b);
    if (from >= hi) return open;
  }
  return open + std::max(hi - from, 0.0);
}

class UnionIntegrator {
 public:
  UnionIntegrator(std::vector<Ball> balls, double accuracy)
      : balls_(std::move(balls)), accuracy_(accuracy) {}

  BallUnionMoments run(const Vec3& reference);

 private:
  static constexpr int kMaxCells = 1 << 18;  // ~60 MB; reached only for accuracy << 1e-4

  Column column(double x, double y, int begin, int count);
  void add_cell(double x, double y, double s, const Column& centre, int parent_begin,
                int parent_count);
  Moments total() const;

  std::vector<Ball> balls_;
  double accuracy_;
  std::vector<int> pool_;  // candidate ball indices of all cells
  std::vector<Cell> cells_;
  std::vector<char> leaf_;
  std::vector<std::pair<double, double>> chords_;   // scratch
  std::vector<std::pair<double, double>> covered_;  // scratch
  long evaluations_ = 0;
};

Column UnionIntegrator::column(double x, double y, int begin, int count) {
  ++evaluations_;
  chords_.clear();
  for (int k = begin; k < begin + count; ++k) {
    const Ball& b = balls_[pool_[k]];
    const double dx = x - b.x, dy = y - b.y;
    const double q = b.r2 - dx * dx - dy * dy;
    if (q > 0.0) {
      const double h = std::sqrt(q);
      chords_.emplace_back(b.z - h, b.z + h);
    }
  }
  // Insertion sort by lower end: few chords, mostly in order already.
  for (std::size_t i = 1; i < chords_.size(); ++i) {
    const auto c = chords_[i];
    std::size_t j = i;
    for (; j > 0 && chords_[j - 1].first > c.first; --j) chords_[j] = chords_[j - 1];
    chords_[j] = c;
  }
  Column out;
  auto flush = [&out](double lo, double hi) {
    const double d = hi - lo;
    out.len += d;
    out.z1 += 0.5 * d * (hi + lo);
    out.z2 += d * (hi * hi + hi * lo + lo * lo) / 3.0;
  };
  if (chords_.empty()) return out;
  double lo = chords_[0].first, hi = chords_[0].second;
  for (std::size_t i = 1; i < chords_.size(); ++i) {
    if (chords_[i].first > hi) {
      flush(lo, hi);
      lo = chords_[i].first;
      hi = chords_[i].second;
    } else {
      hi = std::max(hi, chords_[i].second);
    }
  }
  flush(lo, hi);
  return out;
}

void UnionIntegrator::add_cell(double x, double y, double s, const Column& centre, int parent_begin,
                               int parent_count) {
  // Keep the balls whose disk meets the square: exact, so a cell without candidates
  // is empty and contributes nothing, with no error.
  const int begin = static_cast<int>(pool_.size());
  for (int k = parent_begin; k < parent_begin + parent_count; ++k) {
    const Ball& b = balls_[pool_[k]];
    const double dx = std::max(std::abs(x - b.x) - s, 0.0);
    const double dy = std::max(std::abs(y - b.y) - s, 0.0);
    if (dx * dx + dy * dy < b.r2) pool_.push_back(pool_[k]);
  }
  const int count = static_cast<int>(pool_.size()) - begin;
  if (count == 0) return;

  Cell c;
  c.x = x;
  c.y = y;
  c.s = s;
  c.cand_begin = begin;
  c.cand_count = count;
  const double h = 0.5 * s;
  const double qx[4] = {x - h, x + h, x - h, x + h};
  const double qy[4] = {y - h, y - h, y + h, y + h};
  c.fine.fill(0.0);
  for (int i = 0; i < 4; ++i) {
    c.sub[i] = column(qx[i], qy[i], begin, count);
    const Moments m = column_moments(c.sub[i], qx[i], qy[i], h, s * s);
    for (int k = 0; k < kMomentCount; ++k) c.fine[k] += m[k];
  }
  const Moments coarse = column_moments(centre, x, y, s, 4.0 * s * s);
  Moments diff;
  for (int k = 0; k < kMomentCount; ++k) diff[k] = c.fine[k] - coarse[k];
  // Richardson: the midpoint rule is second order, so halving the cell cuts its error
  // about 4x and the error left in the fine rule is about |fine - coarse| / 3.
  c.err_v = std::abs(diff[kV]) / 3.0;
  c.err_i = inertia_norm(diff) / 3.0;

  // A ball whose disk meets the square but holds none of the five sample points is
  // invisible to both rules, so |fine - coarse| cannot see it (slivers along the
  // silhouettes). Add a bound on what it can contribute: the part of its bounding
  // box inside the square times the part of its longest chord there that is not
  // covered, in every column of the square, by balls whose disk holds the whole square.
  covered_.clear();
  for (int k = begin; k < begin + count; ++k) {
    const Ball& b = balls_[pool_[k]];
    const double fx = std::abs(x - b.x) + s, fy = std::abs(y - b.y) + s;
    const double q = b.r2 - fx * fx - fy * fy;
    if (q > 0.0) {
      const double h_min = std::sqrt(q);
      covered_.emplace_back(b.z - h_min, b.z + h_min);
    }
  }
  bool sorted = false;
  for (int k = begin; k < begin + count; ++k) {
    const Ball& b = balls_[pool_[k]];
    auto inside = [&b](double px, double py) {
      return (px - b.x) * (px - b.x) + (py - b.y) * (py - b.y) < b.r2;
    };
    if (inside(x, y) || inside(qx[0], qy[0]) || inside(qx[1], qy[1]) || inside(qx[2], qy[2]) ||
        inside(qx[3], qy[3])) {
      continue;
    }
    if (!sorted) {
      std::sort(covered_.begin(), covered_.end());
      sorted = true;
    }
    const double dx = std::max(std::abs(x - b.x) - s, 0.0);
    const double dy = std::max(std::abs(y - b.y) - s, 0.0);
    const double h_max = std::sqrt(std::max(b.r2 - dx * dx - dy * dy, 0.0));
    const double open = uncovered_length(b.z - h_max, b.z + h_max, covered_);
    if (open <= 0.0) continue;
    const double wx = std::min(x + s, b.x + b.r) - std::max(x - s, b.x - b.r);
    const double wy = std::min(y + s, b.y + b.r) - std::max(y - s, b.y - b.r);
    const double missed = std::max(wx, 0.0) * std::max(wy, 0.0) * open;
    // ‖|r|²𝟙 - r rᵀ‖_2 = |r|², with |r| bounded over the box the sliver lies in.
    const double rx = std::abs(x) + s, ry = std::abs(y) + s, rz = std::abs(b.z) + h_max;
    c.err_v += missed;
    c.err_i += missed * (rx * rx + ry * ry + rz * rz);
  }
  cells_.push_back(c);
  leaf_.push_back(1);
}

Moments UnionIntegrator::total() const {
  Moments t{};
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    if (!leaf_[i]) continue;
    for (int k = 0; k < kMomentCount; ++k) t[k] += cells_[i].fine[k];
  }
  return t;
}

// Smallest principal moment of the unit-density inertia about the centroid, m⁵.
double smallest_principal_moment(const Moments& t) {
  const Vec3 g(t[kSx] / t[kV], t[kSy] / t[kV], t[kSz] / t[kV]);
  const Mat3 m2 = second_moment_matrix(t) - t[kV] * g * g.transpose();
  const Mat3 inertia = m2.trace() * Mat3::Identity() - m2;
  return Eigen::SelfAdjointEigenSolver<Mat3>(inertia, Eigen::EigenvaluesOnly).eigenvalues()(0);
}

BallUnionMoments UnionIntegrator::run(const Vec3& reference) {
  // Initial grid: fine enough that every ball's disk holds quarter-cell sample
  // points (spacing <= r_min), and at least 16x16 so that the first error estimates
  // are already in the asymptotic regime.
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY, r_min = INFINITY;
  for (const Ball& b : balls_) {
    x0 = std::min(x0, b.x - b.r);
    x1 = std::max(x1, b.x + b.r);
    y0 = std::min(y0, b.y - b.r);
    y1 = std::max(y1, b.y + b.r);
    r_min = std::min(r_min, b.r);
  }
  const double side = std::max(x1 - x0, y1 - y0);
  const int grid = std::clamp(static_cast<int>(std::ceil(side / (2.0 * r_min))), 16, 256);
  const double s0 = side / (2.0 * grid);
  const double cx = 0.5 * (x0 + x1) - side / 2.0, cy = 0.5 * (y0 + y1) - side / 2.0;

  for (std::size_t i = 0; i < balls_.size(); ++i) pool_.push_back(static_cast<int>(i));
  const int all = static_cast<int>(balls_.size());
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      const double x = cx + (2 * i + 1) * s0, y = cy + (2 * j + 1) * s0;
      add_cell(x, y, s0, column(x, y, 0, all), 0, all);
    }
  }

  double err_v = 0.0, err_i = 0.0;
  for (const Cell& c : cells_) {
    err_v += c.err_v;
    err_i += c.err_i;
  }
  Moments t = total();
  double tol_v = accuracy_ * t[kV];
  double tol_i = accuracy_ * smallest_principal_moment(t);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry> queue;
  auto priority = [&](const Cell& c) { return std::max(c.err_v / tol_v, c.err_i / tol_i); };
  for (std::size_t i = 0; i < cells_.size(); ++i) queue.emplace(priority(cells_[i]), i);

  bool converged = false;
  for (;;) {
    while ((err_v > tol_v || err_i > tol_i) && !queue.empty() &&
           cells_.size() + 4 <= static_cast<std::size_t>(kMaxCells)) {
      const int id = queue.top().second;
      queue.pop();
      const Cell parent = cells_[id];  // copy: add_cell may reallocate cells_
      leaf_[id] = 0;
      err_v -= parent.err_v;
      err_i -= parent.err_i;
      const std::size_t first_child = cells_.size();
      const double h = 0.5 * parent.s;
      const double qx[4] = {parent.x - h, parent.x + h, parent.x - h, parent.x + h};
      const double qy[4] = {parent.y - h, parent.y - h, parent.y + h, parent.y + h};
      for (int q = 0; q < 4; ++q) {
        add_cell(qx[q], qy[q], h, parent.sub[q], parent.cand_begin, parent.cand_count);
      }
      for (std::size_t k = first_child; k < cells_.size(); ++k) {
        err_v += cells_[k].err_v;
        err_i += cells_[k].err_i;
        queue.emplace(priority(cells_[k]), static_cast<int>(k));
      }
    }
    // The tolerances were set from a coarser estimate; accept only if they still hold
    // for the refined totals.
    t = total();
    tol_v = accuracy_ * t[kV];
    tol_i = accuracy_ * smallest_principal_moment(t);
    if (err_v <= tol_v && err_i <= tol_i) {
      converged = true;
      break;
    }
    if (queue.empty() || cells_.size() + 4 > static_cast<std::size_t>(kMaxCells)) break;
    // Rebuild priorities with the new tolerances (ordering by them only).
    std::priority_queue<Entry> fresh;
    for (std::size_t i = 0; i < cells_.size(); ++i) {
      if (leaf_[i]) fresh.emplace(priority(cells_[i]), static_cast<int>(i));
    }
    queue.swap(fresh);
  }

  BallUnionMoments out;
  out.volume = t[kV];
  const Vec3 g(t[kSx] / t[kV], t[kSy] / t[kV], t[kSz] / t[kV]);
  out.centroid = reference + g;
  out.second_moment = second_moment_matrix(t) - t[kV] * g * g.transpose();
  // Sums of |δ| over leaves; recomputed in leaf order so that the running sums'
  // rounding cannot leak into the reported figures.
  out.volume_error = 0.0;
  out.inertia_error = 0.0;
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    if (!leaf_[i]) continue;
    out.volume_error += cells_[i].err_v;
    out.inertia_error += cells_[i].err_i;
  }
  out.evaluations = evaluations_;
  out.converged = converged;
  return out;
}

void validate_balls(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                    double accuracy) {
  std::ostringstream s;
  if (!(accuracy >= 1e-5 && accuracy <= 0.1)) {
    s << "union integration 'accuracy' = " << accuracy << " is outside [1e-05, 0.1]";
    throw SetupError(s.str());
  }
  if (centres.empty() || centres.size() != radii.size()) {
    s << "union integration needs as many centres as radii, at least one (got " << centres.size()
      << " centres, " << radii.size() << " radii)";
    throw SetupError(s.str());
  }
  for (std::size_t i = 0; i < radii.size(); ++i) {
    if (!(radii[i] > 0.0 && std::isfinite(radii[i])) || !centres[i].allFinite()) {
      s << "union integration ball " << i << " has radius " << radii[i] << " and centre ("
        << centres[i].transpose() << "); need radius > 0, finite centre";
      throw SetupError(s.str());
    }
  }
}

}  // namespace

BallUnionMoments integrate_ball_union(const std::vector<Vec3>& centres,
                                      const std::vector<double>& radii, double accuracy) {
  validate_balls(centres, radii, accuracy);
  // Reference point: the centroid with overlaps counted twice, close to the true one,
  // so that the moments are taken about a point near the centroid.
  Vec3 reference = Vec3::Zero();
  double weight = 0.0;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    const double w = radii[i] * radii[i] * radii[i];
    reference += w * centres[i];
    weight += w;
  }
  reference /= weight;

  std::vector<Ball> balls;
  balls.reserve(radii.size());
  for (std::size_t i = 0; i < radii.size(); ++i) {
    const Vec3 d = centres[i] - reference;
    balls.push_back(Ball{d.x(), d.y(), d.z(), radii[i], radii[i] * radii[i]});
  }
  // Sorted by the lower end of their longest chord, every candidate list (a filtered
  // subsequence) yields its chords nearly sorted, which keeps the column sort linear.
  std::stable_sort(balls.begin(), balls.end(),
                   [](const Ball& a, const Ball& b) { return a.z - a.r < b.z - b.r; });
  return UnionIntegrator(std::move(balls), accuracy).run(reference);
}

bool balls_overlap(const std::vector<Vec3>& centres, const std::vector<double>& radii) {
  for (std::size_t i = 0; i < radii.size(); ++i) {
    for (std::size_t j = i + 1; j < radii.size(); ++j) {
      if ((centres[i] - centres[j]).norm() < radii[i] + radii[j]) return true;
    }
  }
  return false;
}

BallUnionMoments ball_union_moments(const std::vector<Vec3>& centres,
                                    const std::vector<double>& radii, double accuracy) {
  validate_balls(centres, radii, accuracy);
  if (balls_overlap(centres, radii)) return integrate_ball_union(centres, radii, accuracy);
  // The union is the balls themselves: ∫x xᵀ over a ball about its centre is V r²/5 𝟙.
  BallUnionMoments out;
  Vec3 moment = Vec3::Zero();
  for (std::size_t i = 0; i < radii.size(); ++i) {
    const double v = 4.0 / 3.0 * kPi * radii[i] * radii[i] * radii[i];
    out.volume += v;
    moment += v * centres[i];
  }
  out.centroid = moment / out.volume;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    const double v = 4.0 / 3.0 * kPi * radii[i] * radii[i] * radii[i];
    const Vec3 d = centres[i] - out.centroid;
    out.second_moment += v * (radii[i] * radii[i] / 5.0 * Mat3::Identity() + d * d.transpose());
  }
  out.converged = true;
  return out;
}

}  // namespace ballast
