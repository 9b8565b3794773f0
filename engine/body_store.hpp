// Rigid bodies. Storage is split the Box2D way: the integration state every step
// touches (position, velocity, force...) apart from mass properties and the cold
// bookkeeping (initial position, energy ledger). A body owns a contiguous range of
// balls [first_ball, first_ball + ball_count).
#pragma once

#include <span>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

struct BodyStore {
  // integration state (hot)
  std::vector<Vec3> position;          // centre of mass, m
  std::vector<Vec3> velocity;          // m/s, at the half step t - dt/2 (leapfrog)
  std::vector<Vec3> angular_velocity;  // rad/s, world frame, half step
  std::vector<Vec3> angular_momentum;  // kg·m²/s, world frame, half step (`full` clumps only)
  std::vector<Vec3> force;             // N, resultant (contacts + gravity) at t, before damping
  std::vector<Vec3> torque;            // N·m about the centre of mass, world frame
  std::vector<Quat> orientation;       // body (principal) frame -> world; spheres keep identity
  // mass properties
  std::vector<double> mass;             // kg
  std::vector<double> inv_mass;         // 1/kg
  std::vector<Vec3> inertia;            // principal moments, kg·m² (equal for a sphere)
  std::vector<Vec3> inv_inertia;        // 1/(kg·m²)
  std::vector<Index> first_ball;        // into BallStore
  std::vector<Index> ball_count;        // 1 for a sphere
  std::vector<std::uint8_t> is_sphere;  // one ball at the centre: cheapest rotation path
  // cold: measurement and energy ledger (per body so sums are order-independent)
  std::vector<Vec3> reference_position;    // m, where the body was at the reference time
  std::vector<Vec3> rotation;              // rad, Σ ω·dt since the reference time (PFC's
                                           // accumulated rotation vector; the paper's Figs 13-14)
  std::vector<double> gravity_work;        // J done on this body by gravity
  std::vector<double> damping_dissipated;  // J removed by local damping

  Index size() const { return static_cast<Index>(mass.size()); }

  // Displacement since the reference time, m.
  Vec3 displacement(Index b) const { return position[b] - reference_position[b]; }
  // Magnitude of the accumulated rotation vector since the reference time, rad.
  double rotation_angle(Index b) const { return rotation[b].norm(); }
  // Makes now the reference time: displacements and rotations restart from zero.
  void reset_motion_reference();

  // Appends a body at rest. Mass properties must already be in the principal frame.
  Index add(const Vec3& x, const Quat& q, double m, const Vec3& principal_inertia, Index first,
            Index count, bool sphere);
};

}  // namespace ballast
