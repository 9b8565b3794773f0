// Linked-cell neighbour search. Balls are binned into cubic cells no smaller than
// the largest interaction distance (2·r_max + skin), so every candidate partner of
// a ball lies in its own or one of the 26 surrounding cells.
//
// Layout (HOOMD-style, documented because the force loop depends on it):
//   cell_start[c] .. cell_start[c+1]  is the slice of `cell_balls` holding the balls
//   of cell c, in increasing ball index. Cells are numbered x-fastest.
// Balls outside [lo, hi] are clamped into the border cells, so a stray ball is
// still found; the simulation reports balls that leave the domain separately.
#pragma once

#include <array>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

class CellList {
 public:
  // The grid's cap, in cells per ball (cell_list.cpp, CellList::build).
  static constexpr double kMaxCellsPerBall = 16.0;

  void build(const std::vector<Vec3>& positions, const Vec3& lo, const Vec3& hi,
             double min_cell_size);

  std::array<int, 3> dims() const { return dims_; }
  int cell_of(const Vec3& x) const;
  std::array<int, 3> coords_of(const Vec3& x) const;
  int cell_index(int cx, int cy, int cz) const { return cx + dims_[0] * (cy + dims_[1] * cz); }
  const std::vector<Index>& cell_start() const { return cell_start_; }
  const std::vector<Index>& cell_balls() const { return cell_balls_; }

 private:
  Vec3 lo_ = Vec3::Zero();
  Vec3 inv_size_ = Vec3::Ones();
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<Index> cell_start_;
  std::vector<Index> cell_balls_;
};

// Candidate ball pairs (a < b) closer than r_a + r_b + skin, excluding pairs of the
// same body, sorted by (a, b). Built in parallel but deterministic: each ball's
// partners are collected independently and concatenated in ball order.
void find_candidate_pairs(const CellList& cells, const std::vector<Vec3>& positions,
                          const std::vector<double>& radii, const std::vector<Index>& body,
                          double skin, std::vector<Index>& out_a, std::vector<Index>& out_b);

// The same contract by checking every pair: the oracle the cell list is tested against.
void brute_force_pairs(const std::vector<Vec3>& positions, const std::vector<double>& radii,
                       const std::vector<Index>& body, double skin, std::vector<Index>& out_a,
                       std::vector<Index>& out_b);

}  // namespace ballast
