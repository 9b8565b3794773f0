#include "engine/porosity.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine/errors.hpp"

namespace ballast {
namespace {

double ball_volume(double r) {
  return 4.0 / 3.0 * kPi * r * r * r;
}

bool positive_finite(double x) {
  return std::isfinite(x) && x > 0.0;
}

// Index range [first, last] of the cubes along one axis whose centres
// lo + (i + 1/2)·h may lie in the open interval (a, b), widened by one cube each side
// so that rounding here can never drop a cube (the exact distance test decides), and
// clamped to [0, n − 1]. first > last when the interval misses the grid.
std::array<int, 2> cube_range(double a, double b, double lo, double h, int n) {
  const double first = std::floor((a - lo) / h - 0.5);
  const double last = std::ceil((b - lo) / h - 0.5);
  if (last < 0.0 || first > n - 1.0) return {1, 0};
  return {static_cast<int>(std::max(first, 0.0)), static_cast<int>(std::min(last, n - 1.0))};
}

}  // namespace

double ball_sphere_intersection_volume(double r, double R, double d) {
  // The check sits behind a branch so that the hot path builds no strings.
  if (!positive_finite(r)) require_setup(false, "intersection ball radius", r, "> 0, finite");
  if (!positive_finite(R)) require_setup(false, "intersection sphere radius", R, "> 0, finite");
  if (!(std::isfinite(d) && d >= 0.0))
    require_setup(false, "intersection centre distance", d, ">= 0, finite");

  if (d >= R + r) return 0.0;
  const double small = std::min(r, R);
  const double v_small = ball_volume(small);
  if (d <= std::abs(R - r)) return v_small;

  // Lens. The second factor of the textbook numerator, d² + 2dr − 3r² + 2dR + 6rR − 3R²,
  // is written as d² + 2d(r + R) − 3(R − r)²: the expanded form cancels −3r² + 6rR − 3R²
  // catastrophically when r ≈ R and d is small. Here d > |R − r| >= 0, so the division
  // is safe, and d² > (R − r)², 2d(r + R) > 2(R − r)² keep the factor positive. Near
  // internal tangency it tends to 4d·min(r, R) out of terms of size 2d(r + R): at most
  // log10(max/min radius) digits are lost, 1–2 for a ball against a measurement sphere.
  // The clamp only removes rounding just inside the two case boundaries, where the
  // exact lens tends continuously to 0 and to v_small.
  const double gap = R + r - d;
  const double dr = R - r;
  const double lens = kPi * gap * gap * (d * d + 2.0 * d * (r + R) - 3.0 * dr * dr) / (12.0 * d);
  return std::clamp(lens, 0.0, v_small);
}

MeasurementSphereResult measurement_sphere_porosity(const BallStore& balls, const Vec3& centre,
                                                    double radius) {
  require_setup(positive_finite(radius), "measurement sphere radius", radius, "> 0, finite");
  require_setup(centre.allFinite(), "measurement sphere centre", centre.transpose(), "finite");

  MeasurementSphereResult out;
  out.volume = ball_volume(radius);
  const Index n = balls.size();
  // Serial on purpose: a floating-point sum in index order is the same on any number
  // of threads, and one sphere over 10^5 balls costs well under a millisecond.
  for (Index i = 0; i < n; ++i) {
    const double r = balls.radius[i];
    const double d = (balls.position[i] - centre).norm();
    if (!(d < radius + r)) continue;  // also skips a non-finite position
    out.solid_volume += ball_sphere_intersection_volume(r, radius, d);
    ++out.balls_inside;
    if (d > std::abs(radius - r)) ++out.balls_cut;
  }
  // Not clamped: with clump overlaps counted twice the "solid" may exceed the sphere,
  // and a negative porosity is the honest signal of that.
  out.porosity = 1.0 - out.solid_volume / out.volume;
  return out;
}

GridPorosityResult grid_porosity(const BallStore& balls, const Vec3& lo, const Vec3& hi,
                                 double cube_side) {
  require_setup(positive_finite(cube_side), "grid cube side", cube_side, "> 0, finite");
  require_setup(lo.allFinite(), "grid lo", lo.transpose(), "finite");
  require_setup(hi.allFinite(), "grid hi", hi.transpose(), "finite");
  const char* axis_name[3] = {"x", "y", "z"};
  double total = 1.0;
  GridPorosityResult out;
  for (int a = 0; a < 3; ++a) {
    require_setup(hi[a] > lo[a], std::string("grid hi.") + axis_name[a], hi[a],
                  "> lo." + std::string(axis_name[a]) + " = " + std::to_string(lo[a]));
    const double extent = hi[a] - lo[a];
    const double n = std::max(1.0, std::round(extent / cube_side));
    total *= n;
    // Checked before the cast: 2^31 one-byte cells per layer would not fit anyway.
    require_setup(total <= 2147483648.0, "grid cube count", total, "<= 2^31 (use larger cubes)");
    out.cubes[a] = static_cast<int>(n);
    out.cube_size[a] = extent / n;
  }
  const int nx = out.cubes[0], ny = out.cubes[1], nz = out.cubes[2];
  const Vec3 h = out.cube_size;
  out.total_cubes = static_cast<std::int64_t>(nx) * ny * nz;

  // Bin balls by the layers of cubes (constant z index) they can reach: a counting
  // sort, serial and O(balls + entries), each layer's list in ball index order.
  const Index nb = balls.size();
  std::vector<std::array<int, 2>> reach(nb);
  std::vector<std::int64_t> layer_start(nz + 1, 0);
  for (Index i = 0; i < nb; ++i) {
    const Vec3& x = balls.position[i];
    if (!x.allFinite())
      require_setup(false, "ball " + std::to_string(i) + " position", x.transpose(), "finite");
    const double r = balls.radius[i];
    if (!positive_finite(r))
      require_setup(false, "ball " + std::to_string(i) + " radius", r, "> 0, finite");
    reach[i] = cube_range(x.z() - r, x.z() + r, lo.z(), h.z(), nz);
    for (int k = reach[i][0]; k <= reach[i][1]; ++k) ++layer_start[k + 1];
  }
  for (int k = 0; k < nz; ++k) layer_start[k + 1] += layer_start[k];
  std::vector<Index> layer_balls(layer_start[nz]);
  {
    std::vector<std::int64_t> fill(layer_start.begin(), layer_start.end() - 1);
    for (Index i = 0; i < nb; ++i)
      for (int k = reach[i][0]; k <= reach[i][1]; ++k) layer_balls[fill[k]++] = i;
  }

  // Each layer is rasterised into its own nx × ny mask, so threads never share a
  // cell; the integer sum is exact, hence independent of the thread count and of
  // the schedule (dynamic, because layers near a free surface hold fewer balls).
  std::int64_t solid = 0;
#pragma omp parallel reduction(+ : solid)
  {
    std::vector<unsigned char> mask(static_cast<std::size_t>(nx) * ny);
#pragma omp for schedule(dynamic, 1)
    for (int k = 0; k < nz; ++k) {
      std::fill(mask.begin(), mask.end(), 0);
      const double zc = lo.z() + (k + 0.5) * h.z();
      for (std::int64_t e = layer_start[k]; e < layer_start[k + 1]; ++e) {
        const Index b = layer_balls[e];
        const Vec3& x = balls.position[b];
        const double r2 = balls.radius[b] * balls.radius[b];
        const double dz = zc - x.z();
        const double rho2 = r2 - dz * dz;  // squared radius of the ball's disc in this layer
        if (rho2 <= 0.0) continue;
        const double rho = std::sqrt(rho2);
        const auto jr = cube_range(x.y() - rho, x.y() + rho, lo.y(), h.y(), ny);
        for (int j = jr[0]; j <= jr[1]; ++j) {
          const double dy = lo.y() + (j + 0.5) * h.y() - x.y();
          const double chord2 = rho2 - dy * dy;
          if (chord2 <= 0.0) continue;
          const double chord = std::sqrt(chord2);
          const auto ir = cube_range(x.x() - chord, x.x() + chord, lo.x(), h.x(), nx);
          unsigned char* row = mask.data() + static_cast<std::size_t>(j) * nx;
          for (int i = ir[0]; i <= ir[1]; ++i) {
            const double dx = lo.x() + (i + 0.5) * h.x() - x.x();
            // The definition itself, not the chord: the ranges above only prune.
            if (dx * dx + dy * dy + dz * dz < r2) row[i] = 1;
          }
        }
      }
      std::int64_t layer_solid = 0;
      for (unsigned char m : mask) layer_solid += m;
      solid += layer_solid;
    }
  }
  out.solid_cubes = solid;
  out.porosity =
      static_cast<double>(out.total_cubes - solid) / static_cast<double>(out.total_cubes);
  return out;
}

}  // namespace ballast
