#include "engine/cell_list.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "engine/ordered_pairs.hpp"

namespace ballast {

void CellList::build(const std::vector<Vec3>& positions, const Vec3& lo, const Vec3& hi,
                     double min_cell_size) {
  lo_ = lo;
  const Vec3 extent = hi - lo;
  const Index n = static_cast<Index>(positions.size());
  // Cap the grid at kMaxCellsPerBall cells a ball (and 1024 along an axis). With the
  // axis cap alone (up to 10⁹ cells), tiny balls in a large domain (a clump of
  // extension D3 = 100 has balls of 0.3 % of its size) spent half a 2-minute run in
  // the kernel, allocating and clearing the grid at every build. Larger cells find
  // the same pairs, in the same sorted order, with more distance tests.
  const double max_cells = kMaxCellsPerBall * std::max(1.0, double(n));
  std::size_t ncell = 0;
  // At most 200 enlargements (a factor 4e19): a domain of infinite extent (a box
  // 1e308 m high) never gets under the cap and keeps 1024 cells along that axis.
  double size = min_cell_size;
  for (int tries = 0; tries < 200; ++tries, size *= 1.25) {
    for (int a = 0; a < 3; ++a) {
      const double cells = std::floor(extent[a] / size);
      dims_[a] = static_cast<int>(std::clamp(cells, 1.0, 1024.0));
      inv_size_[a] = dims_[a] / extent[a];
    }
    ncell = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
    if (double(ncell) <= max_cells) break;
  }

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

// A ball as the search reads it, copied in cell order so that the balls of a cell
// are read from consecutive memory rather than gathered from the ball arrays one
// cache line each.
struct PackedBall {
  double x, y, z, r;
  Index ball, body;
};

std::vector<PackedBall> pack_by_cell(const CellList& cells, const std::vector<Vec3>& x,
                                     const std::vector<double>& r, const std::vector<Index>& body) {
  const std::vector<Index>& order = cells.cell_balls();
  std::vector<PackedBall> packed(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Index i = order[k];
    packed[k] = {x[i].x(), x[i].y(), x[i].z(), r[i], i, body[i]};
  }
  return packed;
}

// Appends to `out` every ball b > a in the 27 cells around ball a that is within
// reach and belongs to another body. Branch-free: every ball of a row of cells is
// written to the next slot and the slot advances by the test's 0/1, since which of
// them pass follows no pattern a predictor could learn.
void scan_partners(const CellList& cells, const std::vector<PackedBall>& packed, const Vec3& xa,
                   double ra, Index body_a, double skin, Index a, std::vector<Index>& out) {
  const auto c = cells.coords_of(xa);
  const auto d = cells.dims();
  const auto& start = cells.cell_start();
  for (int dz = -1; dz <= 1; ++dz) {
    const int cz = c[2] + dz;
    if (cz < 0 || cz >= d[2]) continue;
    for (int dy = -1; dy <= 1; ++dy) {
      const int cy = c[1] + dy;
      if (cy < 0 || cy >= d[1]) continue;
      const int cx0 = std::max(c[0] - 1, 0), cx1 = std::min(c[0] + 1, d[0] - 1);
      // Cells are numbered x-fastest: the row's cells are one slice of `packed`.
      const Index k0 = start[cells.cell_index(cx0, cy, cz)];
      const Index k1 = start[cells.cell_index(cx1, cy, cz) + 1];
      std::size_t w = out.size();
      out.resize(w + std::size_t(k1 - k0));
      Index* const slot = out.data();
      for (Index k = k0; k < k1; ++k) {
        const PackedBall& q = packed[k];
        const double reach = ra + q.r + skin;
        const double ex = q.x - xa.x(), ey = q.y - xa.y(), ez = q.z - xa.z();
        const bool keep =
            (q.ball > a) & (q.body != body_a) & (ex * ex + ey * ey + ez * ez < reach * reach);
        slot[w] = q.ball;
        w += keep;
      }
      out.resize(w);
    }
  }
}

}  // namespace

void find_candidate_pairs(const CellList& cells, const std::vector<Vec3>& positions,
                          const std::vector<double>& radii, const std::vector<Index>& body,
                          double skin, std::vector<Index>& out_a, std::vector<Index>& out_b) {
  const std::vector<PackedBall> packed = pack_by_cell(cells, positions, radii, body);
  // One scan per ball, appending as it goes (a count pass and then a fill pass into
  // per-ball slices scanned the cells twice).
  const auto scan = [&](Index lo, Index hi, std::vector<Index>& pa, std::vector<Index>& pb) {
    for (Index a = lo; a < hi; ++a) {
      const std::size_t first = pb.size();
      scan_partners(cells, packed, positions[a], radii[a], body[a], skin, a, pb);
      std::sort(pb.begin() + std::ptrdiff_t(first), pb.end());
      pa.resize(pb.size(), a);
    }
  };
  collect_pairs_in_order(Index(positions.size()), scan, out_a, out_b);
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
