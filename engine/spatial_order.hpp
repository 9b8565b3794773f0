// A spatial numbering of bodies, for beds that arrive in another order (a packing
// file from another code, a hand-built scene).
//
// Why it matters: the force pass walks the balls by index, and the threads split
// the bodies by index. Bodies numbered cell by cell keep a contact's two balls near
// each other in memory, and put the boundary between two threads' shares across
// one section of the bed, so few contacts straddle it. A shuffled file loses about
// 7 % on one thread and a quarter on two (docs/PERFORMANCE.md, "Beds from
// elsewhere"). LAMMPS (`atom_modify sort`) and HOOMD (`SFCPackTuner`) sort for the
// same reason.
//
// The order: cubic cells of the largest body's diameter; cells taken with the axis
// across the bed's smallest section slowest (the threads' boundary cuts it), then
// the others in the order z, y, x, as the bed generator numbers its spheres
// (cases/sphere_packing.hpp); within a cell by position. It depends only on the
// positions, never on the order they came in: two shufflings of one bed sort to
// the same numbering, so to the same bits.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

struct SpatialOrder {
  // order[k]: the index before sorting of the body that becomes body k.
  std::vector<Index> order;
  int slowest_axis = 0;  // 0 x, 1 y, 2 z
  double cell = 0.0;     // m, side of the cubic cells
  // Mean distance between bodies consecutive in the numbering, in cells: before and
  // after sorting. A bed numbered cell by cell steps about one cell; a shuffled one,
  // a good part of the box.
  double step_before = 0.0, step_after = 0.0;
  // Sorting pays when it shortens the mean step by more than kPaysRatio. Beds from
  // our generator (numbered cell by cell in cells of one sphere) come out below it
  // before they settle, and a settled sphere bed exported from a box test too (2.44
  // against 1.79 sorted); a settled Sample 1 bed does not (1.88 against 1.22, in the
  // clumps' larger cells) and is renumbered when it is read back, at the same speed
  // (docs/PERFORMANCE.md, "Beds from elsewhere").
  static constexpr double kPaysRatio = 1.5;
  bool pays() const { return step_before > kPaysRatio * step_after; }
  bool applied = false;  // Simulation::sort_bodies_spatially renumbered the bodies
};

// The numbering for bodies at `centre` whose largest diameter is `diameter` (m, > 0).
SpatialOrder spatial_order(std::span<const Vec3> centre, double diameter);

// One line for a log: what was decided and the mean steps before and after.
std::string describe(const SpatialOrder& o);

// Mean distance between consecutive entries of `order`, in units of `cell`.
double mean_order_step(std::span<const Vec3> centre, std::span<const Index> order, double cell);

}  // namespace ballast
