// The walls of a sphere scene as the SIMD kernel reads them (sphere_kernel.hpp,
// SpherePlaneView): one row per wall, and whether the kernel may take the planes'
// contacts at all.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/contact_list.hpp"
#include "engine/pair_table.hpp"
#include "engine/sphere_kernel.hpp"
#include "engine/walls.hpp"

namespace ballast {

struct PlaneTable {
  // Per wall, kPlaneRow doubles: unit normal, a point on the plane (m), velocity (m/s);
  // zeros for a wall of another shape.
  std::vector<double> rows;
  std::vector<std::uint8_t> is_plane;  // per wall
  // The kernel takes the planes' candidates, then the scalar pass the others', which
  // sums each ball's wrench in the scalar order only when no plane follows a wall of
  // another shape in the list (a ball's candidates come in wall order).
  bool planes_in_lanes = false;
  bool other_shapes = false;  // some wall is not a plane (the sleeper's box)
};

// Fills `t` for this step's walls (they move: servo, prescribed motion), keeping its
// storage from step to step. Simulation::step makes it once per step, before the
// force pass's threads read it.
void fill_plane_table(const std::vector<Wall>& walls, PlaneTable& t);

// The kernel's view of the wall candidates: the balls' arrays and the step as the
// ball–ball kernel's view `k` has them, the table's rows, the wall list's arrays;
// friction: the scene's (not read off `k`, whose shear array is null when there is no
// ball–ball candidate); ledger: book the slip work.
SpherePlaneView sphere_plane_view(const SphereKernelView& k, const PlaneTable& planes,
                                  const PairTable& pairs, ContactList& wall_contacts, bool friction,
                                  bool ledger);

}  // namespace ballast
