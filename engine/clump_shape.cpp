#include "engine/clump_shape.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>

#include "engine/ball_union_integral.hpp"

namespace ballast {
namespace {

// Spherical Fibonacci point set of n points on the unit sphere: equal-area latitude
// bands z_k = 1 - (2k+1)/n, longitudes stepped by the golden angle. Its error for the
// area of a spherical cap falls roughly like n^(-3/4). Cached per n (powers of two).
const std::vector<Vec3>& fibonacci_points(int n) {
  static std::mutex mutex;
  static std::map<int, std::vector<Vec3>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto [it, fresh] = cache.try_emplace(n);
  if (fresh) {
    const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
    it->second.reserve(n);
    for (int k = 0; k < n; ++k) {
      const double z = 1.0 - (2.0 * k + 1.0) / n;
      const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = golden_angle * k;
      it->second.emplace_back(rho * std::cos(phi), rho * std::sin(phi), z);
    }
  }
  return it->second;
}

// Smallest power of two >= max(64, x).
int point_count(double x) {
  int n = 64;
  while (n < x && n < (1 << 20)) n *= 2;
  return n;
}

}  // namespace

double union_surface_area(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                          int points_on_largest) {
  const std::size_t n = radii.size();
  double r_max = 0.0;
  for (double r : radii) r_max = std::max(r_max, r);
  double area = 0.0;
  std::vector<std::size_t> neighbours;
  for (std::size_t i = 0; i < n; ++i) {
    neighbours.clear();
    bool hidden = false;
    for (std::size_t j = 0; j < n && !hidden; ++j) {
      if (j == i) continue;
      const double d = (centres[i] - centres[j]).norm();
      if (d >= radii[i] + radii[j]) continue;  // apart or touching: no cover
      // Inside another ball, or a duplicate of an earlier one: no exposed surface.
      const bool duplicate = d == 0.0 && radii[i] == radii[j];
      if ((duplicate && j < i) || (!duplicate && d + radii[i] <= radii[j])) hidden = true;
      if (!duplicate) neighbours.push_back(j);
    }
    if (hidden) continue;
    const double share = (radii[i] / r_max) * (radii[i] / r_max);
    const std::vector<Vec3>& points = fibonacci_points(point_count(points_on_largest * share));
    long exposed = 0;
    for (const Vec3& u : points) {
      const Vec3 p = centres[i] + radii[i] * u;
      bool covered = false;
      for (std::size_t j : neighbours) {
        if ((p - centres[j]).squaredNorm() < radii[j] * radii[j]) {
          covered = true;
          break;
        }
      }
      if (!covered) ++exposed;
    }
    area += 4.0 * kPi * radii[i] * radii[i] * static_cast<double>(exposed) /
            static_cast<double>(points.size());
  }
  return area;
}

ClumpShape measure_clump_shape(const ClumpTemplate& t, double virtual_radius,
                               const ClumpShapeOptions& o) {
  ClumpShape s;
  s.balls = t.ball_count();
  s.union_volume = t.mass_mode == MassMode::kUniform
                       ? t.volume
                       : ball_union_moments(t.offsets, t.radii, o.volume_accuracy).volume;
  s.surface_area = union_surface_area(t.offsets, t.radii, o.surface_points);
  s.sphericity = std::cbrt(kPi) * std::pow(6.0 * s.union_volume, 2.0 / 3.0) / s.surface_area;
  // Offsets are in the principal frame, so the principal axes are the coordinate axes.
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (int i = 0; i < s.balls; ++i) {
    lo = lo.cwiseMin(t.offsets[i] - Vec3::Constant(t.radii[i]));
    hi = hi.cwiseMax(t.offsets[i] + Vec3::Constant(t.radii[i]));
  }
  double ext[3] = {hi.x() - lo.x(), hi.y() - lo.y(), hi.z() - lo.z()};
  std::sort(ext, ext + 3, [](double u, double v) { return u > v; });
  s.a = ext[0];
  s.b = ext[1];
  s.c = ext[2];
  s.elongation = s.b / s.a;
  s.flatness = s.c / s.b;
  s.volume_ratio = s.union_volume / (4.0 / 3.0 * kPi * std::pow(virtual_radius, 3));
  return s;
}

std::vector<ClumpShape> measure_clump_shapes(const std::vector<ClumpTemplate>& clumps,
                                             double virtual_radius, const ClumpShapeOptions& o) {
  const long n = static_cast<long>(clumps.size());
  std::vector<ClumpShape> shapes(n);
  std::vector<std::exception_ptr> errors(n);
#pragma omp parallel for schedule(dynamic, 16)
  for (long i = 0; i < n; ++i) {
    try {
      shapes[i] = measure_clump_shape(clumps[i], virtual_radius, o);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  }
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  return shapes;
}

StatSummary summarize(const std::vector<double>& v) {
  StatSummary s;
  if (v.empty()) return s;
  s.min = s.max = v[0];
  double sum = 0.0;
  for (double x : v) {
    sum += x;
    s.min = std::min(s.min, x);
    s.max = std::max(s.max, x);
  }
  s.mean = sum / static_cast<double>(v.size());
  if (v.size() > 1) {
    double sq = 0.0;
    for (double x : v) sq += (x - s.mean) * (x - s.mean);
    s.stddev = std::sqrt(sq / static_cast<double>(v.size() - 1));
  }
  return s;
}

ClumpShapeSummary summarize_shapes(const std::vector<ClumpShape>& shapes) {
  ClumpShapeSummary out;
  out.count = static_cast<int>(shapes.size());
  auto field = [&shapes](auto get) {
    std::vector<double> v;
    v.reserve(shapes.size());
    for (const ClumpShape& s : shapes) v.push_back(static_cast<double>(get(s)));
    return summarize(v);
  };
  out.balls = field([](const ClumpShape& s) { return s.balls; });
  out.union_volume = field([](const ClumpShape& s) { return s.union_volume; });
  out.surface_area = field([](const ClumpShape& s) { return s.surface_area; });
  out.sphericity = field([](const ClumpShape& s) { return s.sphericity; });
  out.a = field([](const ClumpShape& s) { return s.a; });
  out.b = field([](const ClumpShape& s) { return s.b; });
  out.c = field([](const ClumpShape& s) { return s.c; });
  out.elongation = field([](const ClumpShape& s) { return s.elongation; });
  out.flatness = field([](const ClumpShape& s) { return s.flatness; });
  out.volume_ratio = field([](const ClumpShape& s) { return s.volume_ratio; });
  return out;
}

}  // namespace ballast
