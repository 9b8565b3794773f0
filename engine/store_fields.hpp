// The field lists of the ball and body stores: every per-ball and per-body vector,
// named once. A checkpoint writes and reads through them (simulation_state.cpp) and
// the spatial sort permutes through them (simulation_order.cpp), so a field added to
// a store and to its list is saved, restored and renumbered alike. The resume tests
// (tests/test_checkpoint.cpp) and the sort tests (tests/test_spatial_order.cpp)
// fail when a field is missing here.
#pragma once

#include "engine/ball_store.hpp"
#include "engine/body_store.hpp"

namespace ballast {

template <class Io>
void state_fields(Io& io, BallStore& b) {
  io(b.position, b.radius, b.body, b.material, b.offset, b.friction_dissipated,
     b.viscous_dissipated);
}

template <class Io>
void state_fields(Io& io, BodyStore& b) {
  io(b.position, b.velocity, b.angular_velocity, b.angular_momentum, b.force, b.torque,
     b.orientation, b.mass, b.inv_mass, b.inertia, b.inv_inertia, b.first_ball, b.ball_count,
     b.is_sphere, b.reference_position, b.rotation, b.gravity_work, b.damping_dissipated);
}

}  // namespace ballast
