#include "engine/spatial_order.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace ballast {

double mean_order_step(std::span<const Vec3> centre, std::span<const Index> order, double cell) {
  if (order.size() < 2) return 0.0;
  double sum = 0.0;  // in order: the same bits on any machine and thread count
  for (std::size_t k = 1; k < order.size(); ++k)
    sum += (centre[std::size_t(order[k])] - centre[std::size_t(order[k - 1])]).norm();
  return sum / (double(order.size() - 1) * cell);
}

std::string describe(const SpatialOrder& o) {
  std::ostringstream out;
  out.precision(3);
  const char axis = "xyz"[o.slowest_axis];
  if (o.applied)
    out << "bodies renumbered cell by cell, " << axis << " slowest: mean step between "
        << "consecutive bodies " << o.step_before << " -> " << o.step_after << " cells of "
        << o.cell * 1e3 << " mm";
  else
    out << "numbering kept: mean step between consecutive bodies " << o.step_before << " cells of "
        << o.cell * 1e3 << " mm (" << o.step_after << " sorted with " << axis
        << " slowest; sorting pays above " << SpatialOrder::kPaysRatio << "x)";
  return out.str();
}

SpatialOrder spatial_order(std::span<const Vec3> centre, double diameter) {
  if (!(diameter > 0.0) || !std::isfinite(diameter))
    throw std::invalid_argument("spatial_order: body diameter = " + std::to_string(diameter) +
                                " m (allowed: finite, > 0)");
  SpatialOrder out;
  out.cell = diameter;
  const std::size_t n = centre.size();
  std::vector<Index> identity(n);
  std::iota(identity.begin(), identity.end(), Index(0));
  if (n == 0) return out;

  Vec3 lo = centre[0], hi = centre[0];
  for (const Vec3& c : centre) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  // The bed's extent along each axis (a body's diameter beyond its centres), and
  // its sections across x, y and z; ties go to z, then y, as in the generator.
  const Vec3 extent = hi - lo + Vec3::Constant(diameter);
  const double section[3] = {extent.y() * extent.z(), extent.x() * extent.z(),
                             extent.x() * extent.y()};
  int slowest = 2;
  for (int k : {1, 0})
    if (section[k] < section[slowest]) slowest = k;
  out.slowest_axis = slowest;
  std::array<int, 3> axes{slowest, 0, 0};
  for (int k = 2, m = 1; k >= 0; --k)
    if (k != slowest) axes[std::size_t(m++)] = k;

  // Cell coordinates, slowest axis first; then the position itself in the same axis
  // order, so that the numbering never depends on the order the bodies came in.
  struct Key {
    std::array<long, 3> cell;
    std::array<double, 3> x;
    Index index;
  };
  std::vector<Key> keys(n);
  for (std::size_t k = 0; k < n; ++k) {
    Key& key = keys[k];
    for (std::size_t a = 0; a < 3; ++a) {
      const int axis = axes[a];
      key.cell[a] = static_cast<long>(std::floor((centre[k][axis] - lo[axis]) / diameter));
      key.x[a] = centre[k][axis];
    }
    key.index = Index(k);
  }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    if (a.cell != b.cell) return a.cell < b.cell;
    if (a.x != b.x) return a.x < b.x;
    return a.index < b.index;  // two bodies at one point: the order they came in
  });
  out.order.resize(n);
  for (std::size_t k = 0; k < n; ++k) out.order[k] = keys[k].index;
  out.step_before = mean_order_step(centre, identity, diameter);
  out.step_after = mean_order_step(centre, out.order, diameter);
  return out;
}

}  // namespace ballast
