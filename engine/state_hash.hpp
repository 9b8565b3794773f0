// 64-bit fingerprints of the dynamic state, for determinism tests: two runs agree
// bit for bit iff (barring a 2^-64 collision) their hashes agree.
#pragma once

#include <cstdint>

#include "engine/body_store.hpp"

namespace ballast {

class Simulation;

// Everything dynamic a run reports, so that "the same hash" means "the same run":
// the bodies' motion (motion_hash), their force and torque of the last step, both
// contact lists' keys, histories and normal forces, the energy ledger per body, ball
// and contact and its totals with the cumulative work and dissipation
// (Simulation::energy()), the walls' geometry, velocities and displacements, the
// servos' state, and the clock.
std::uint64_t state_hash(const Simulation& sim);

// The bodies' motion alone: positions, velocities, angular velocities and momenta,
// orientations, accumulated rotations and displacement references. For runs whose
// contact bookkeeping may differ while the motion must not (early neighbour builds
// flush the dissipation ledger and remake the lists at other steps).
std::uint64_t motion_hash(const BodyStore& bodies);

}  // namespace ballast
