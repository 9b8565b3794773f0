#include "cases/sphere_packing.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace ballast {

int smallest_settled_section(double solid_volume, const Vec3& lo, const Vec3& hi) {
  const double lx = hi.x() - lo.x(), ly = hi.y() - lo.y();
  const double height = solid_volume / (0.6 * lx * ly);
  // Sections across x, y and z of a bed lx × ly × height; ties go to z, then y
  // (the order of the comparisons). Only a bed higher than its floor is wide (a
  // column) keeps z slowest.
  const double section[3] = {ly * height, lx * height, lx * ly};
  int best = 2;
  for (int k : {1, 0})
    if (section[k] < section[best]) best = k;
  return best;
}

std::vector<Vec3> random_loose_packing(int count, double radius, const Vec3& lo, const Vec3& hi,
                                       double volume_fraction, std::uint64_t seed) {
  if (count < 0)
    throw std::invalid_argument("sphere count = " + std::to_string(count) + " (allowed: >= 0)");
  if (!(radius > 0.0))
    throw std::invalid_argument("sphere radius = " + std::to_string(radius) + " (allowed: > 0 m)");
  if (!(volume_fraction > 0.0 && volume_fraction <= 0.35))
    throw std::invalid_argument("volume_fraction = " + std::to_string(volume_fraction) +
                                " (allowed: (0, 0.35]; random addition jams above that)");
  const double sphere_volume = 4.0 / 3.0 * kPi * radius * radius * radius;
  const double area = (hi.x() - lo.x()) * (hi.y() - lo.y());
  double top = lo.z() + 2.0 * radius + count * sphere_volume / (volume_fraction * area);
  // A caller that sizes the region first and works the fraction out from its height
  // (the box test: box_test_prepare.cpp) gets that height back only up to rounding,
  // sometimes a few ulps above it: that is a fit, not a region too low.
  const double rounding = 1e-12 * (hi.z() - lo.z());
  if (top > hi.z() + rounding || hi.x() - lo.x() < 2 * radius || hi.y() - lo.y() < 2 * radius)
    throw std::invalid_argument(
        "sphere count = " + std::to_string(count) +
        " does not fit: it needs the region to reach z = " + std::to_string(top) + " m");
  top = std::min(top, hi.z());
  const Vec3 a = lo + Vec3::Constant(radius);
  const Vec3 b(hi.x() - radius, hi.y() - radius, top - radius);

  // Grid of cells of one diameter: a new sphere only needs checking against the 27
  // cells around it.
  const double cell = 2.0 * radius;
  int n[3];
  for (int k = 0; k < 3; ++k) n[k] = std::max(1, static_cast<int>((b[k] - a[k]) / cell) + 1);
  std::vector<std::vector<int>> grid(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
  auto coord = [&](const Vec3& p, int k) {
    return std::clamp(static_cast<int>((p[k] - a[k]) / cell), 0, n[k] - 1);
  };

  std::mt19937_64 rng(seed);
  std::vector<Vec3> out;
  out.reserve(count);
  const long max_tries = 1000L * count + 1000;
  for (long tries = 0; static_cast<int>(out.size()) < count; ++tries) {
    if (tries > max_tries)
      throw std::invalid_argument("sphere count = " + std::to_string(count) +
                                  ": random addition could not place them all");
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = a[k] + (b[k] - a[k]) * unit_uniform(rng());
    const int cx = coord(p, 0), cy = coord(p, 1), cz = coord(p, 2);
    bool free = true;
    for (int z = std::max(0, cz - 1); free && z <= std::min(n[2] - 1, cz + 1); ++z)
      for (int y = std::max(0, cy - 1); free && y <= std::min(n[1] - 1, cy + 1); ++y)
        for (int x = std::max(0, cx - 1); free && x <= std::min(n[0] - 1, cx + 1); ++x)
          for (int j : grid[x + n[0] * (y + n[1] * z)])
            if ((out[j] - p).squaredNorm() < cell * cell) {
              free = false;
              break;
            }
    if (!free) continue;
    grid[cx + n[0] * (cy + n[1] * cz)].push_back(static_cast<int>(out.size()));
    out.push_back(p);
  }
  // Hand the centres back cell by cell: bodies created in this order have neighbours
  // with nearby indices, so each thread's share of contacts and bodies touches
  // mostly its own memory. The threads split the bodies by index, so the slowest
  // axis of the order is the one their boundary cuts, and the balls within a contact
  // of that boundary are read by one core and written by the other every step. The
  // cloud falls along −z into a bed of about the footprint × the height it has at a
  // packing fraction of 0.6, so the slowest axis is the one across which that bed's
  // section is smallest: for the paper's 700 × 300 mm box a section of 300 mm × the
  // bed's height, not the 700 × 300 mm footprint, which halved the balls near the
  // boundary and gave the sphere bench bed 6 % more of its two-thread bound
  // (docs/PERFORMANCE.md, "Numbering along the bed's smallest section").
  // The other two axes follow in the order z, y, x.
  const int slowest = smallest_settled_section(count * sphere_volume, lo, hi);
  int axes[3] = {slowest, 0, 0};
  for (int k = 2, m = 1; k >= 0; --k)
    if (k != slowest) axes[m++] = k;
  int stride[3];
  stride[axes[2]] = 1;
  stride[axes[1]] = n[axes[2]];
  stride[axes[0]] = n[axes[2]] * n[axes[1]];
  std::vector<std::vector<int>> ordered_cells(grid.size());
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x)
        ordered_cells[std::size_t(x * stride[0] + y * stride[1] + z * stride[2])] =
            std::move(grid[std::size_t(x + n[0] * (y + n[1] * z))]);
  std::vector<Vec3> ordered;
  ordered.reserve(out.size());
  for (const auto& cell_members : ordered_cells)
    for (int j : cell_members) ordered.push_back(out[j]);
  return ordered;
}

}  // namespace ballast
