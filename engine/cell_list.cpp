#include "engine/cell_list.hpp"

#include <algorithm>
#include <cmath>

namespace ballast {

void CellList::build(const std::vector<Vec3>& positions, const Vec3& lo, const Vec3& hi,
                     double min_cell_size) {
  lo_ = lo;
  const Vec3 extent = hi - lo;
  for (int a = 0; a < 3; ++a) {
    // Cap the grid so a tiny cell size cannot allocate billions of cells.
    const double n = std::floor(extent[a] / min_cell_size);
    dims_[a] = static_cast<int>(std::clamp(n, 1.0, 1024.0));
    inv_size_[a] = dims_[a] / extent[a];
  }
  const std::size_t ncell = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  const Index n = static_cast<Index>(positions.size());

  // Counting sort by cell: serial, O(n), and it keeps balls in index order per cell.
  std::vector<int> cell(n);
  cell_start_.assign(ncell + 1, 0);
  for (Index i = 0; i < n; ++i) {
    cell[i] = cell_of(positions[i]);
    ++cell_start_[cell[i] + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
  std::vector<Index> fill(cell_start_.begin(), cell_start_.end() - 1);
  cell_balls_.resize(n);
  for (Index i = 0; i < n; ++i) cell_balls_[fill[cell[i]]++] = i;
}

std::array<int, 3> CellList::coords_of(const Vec3& x) const {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const double f = std::floor((x[a] - lo_[a]) * inv_size_[a]);
    c[a] = static_cast<int>(std::clamp(f, 0.0, static_cast<double>(dims_[a] - 1)));
  }
  return c;
}

int CellList::cell_of(const Vec3& x) const {
  const auto c = coords_of(x);
  return cell_index(c[0], c[1], c[2]);
}

namespace {

// Calls visit(b) for every ball b > a in the 27 cells around ball a that is within
// reach and belongs to another body.
template <class Visit>
void scan_partners(const CellList& cells, const std::vector<Vec3>& x, const std::vector<double>& r,
                   const std::vector<Index>& body, double skin, Index a, Visit&& visit) {
  const auto c = cells.coords_of(x[a]);
  const auto d = cells.dims();
  const auto& start = cells.cell_start();
  const auto& balls = cells.cell_balls();
  for (int dz = -1; dz <= 1; ++dz) {
    const int cz = c[2] + dz;
    if (cz < 0 || cz >= d[2]) continue;
    for (int dy = -1; dy <= 1; ++dy) {
      const int cy = c[1] + dy;
      if (cy < 0 || cy >= d[1]) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        const int cx = c[0] + dx;
        if (cx < 0 || cx >= d[0]) continue;
        const int cell = cells.cell_index(cx, cy, cz);
        for (Index k = start[cell]; k < start[cell + 1]; ++k) {
          const Index b = balls[k];
          if (b <= a || body[b] == body[a]) continue;
          const double reach = r[a] + r[b] + skin;
          if ((x[b] - x[a]).squaredNorm() < reach * reach) visit(b);
        }
      }
    }
  }
}

}  // namespace

void find_candidate_pairs(const CellList& cells, const std::vector<Vec3>& positions,
                          const std::vector<double>& radii, const std::vector<Index>& body,
                          double skin, std::vector<Index>& out_a, std::vector<Index>& out_b) {
  const Index n = static_cast<Index>(positions.size());
  // Two passes (count, then fill) so each ball writes its own slice: no locks, and
  // the result does not depend on how OpenMP splits the loop.
  std::vector<Index> offset(n + 1, 0);
#pragma omp parallel for schedule(static)
  for (Index a = 0; a < n; ++a) {
    Index count = 0;
    scan_partners(cells, positions, radii, body, skin, a, [&](Index) { ++count; });
    offset[a + 1] = count;
  }
  for (Index a = 0; a < n; ++a) offset[a + 1] += offset[a];
  out_a.resize(offset[n]);
  out_b.resize(offset[n]);
#pragma omp parallel for schedule(static)
  for (Index a = 0; a < n; ++a) {
    Index k = offset[a];
    scan_partners(cells, positions, radii, body, skin, a, [&](Index b) {
      out_a[k] = a;
      out_b[k++] = b;
    });
    std::sort(out_b.begin() + offset[a], out_b.begin() + offset[a + 1]);
  }
}

void brute_force_pairs(const std::vector<Vec3>& positions, const std::vector<double>& radii,
                       const std::vector<Index>& body, double skin, std::vector<Index>& out_a,
                       std::vector<Index>& out_b) {
  out_a.clear();
  out_b.clear();
  const Index n = static_cast<Index>(positions.size());
  for (Index a = 0; a < n; ++a)
    for (Index b = a + 1; b < n; ++b) {
      if (body[a] == body[b]) continue;
      const double reach = radii[a] + radii[b] + skin;
      if ((positions[b] - positions[a]).squaredNorm() < reach * reach) {
        out_a.push_back(a);
        out_b.push_back(b);
      }
    }
}

}  // namespace ballast
