// The force loop: evaluate every candidate contact, then gather the results into
// body forces and torques. Two passes instead of one scatter so that no two threads
// ever add into the same number: a contact writes only its own slots, a body reads
// only its own balls' contacts, in a fixed order. That is what makes 1 and 2
// threads bit-identical without atomics.
//
// The loops are orphaned `omp for` constructs: Simulation::step calls them inside
// one parallel region, so a step pays one fork/join instead of one per loop.
// Called outside a parallel region they simply run serially.
#pragma once

#include <vector>

#include "engine/ball_store.hpp"
#include "engine/body_store.hpp"
#include "engine/contact_list.hpp"
#include "engine/material.hpp"
#include "engine/walls.hpp"

namespace ballast {

struct ForceSettings {
  double dt = 0.0;             // s
  double damping_ratio = 0.0;  // viscous contact damping ratio β (0: none)
  bool friction = true;        // false: frictionless scene, no shear history
};

// Ball–ball contacts: fills force, point, normal_force, works and active flags.
// Both contact loops end without a barrier (`nowait`): inside a parallel region the
// caller must put `#pragma omp barrier` before anything reads their results.
void compute_ball_contacts(const BallStore& balls, const BodyStore& bodies,
                           const std::vector<Material>& materials, const ForceSettings& s,
                           ContactList& contacts);

// Ball–wall contacts (b = wall index).
void compute_wall_contacts(const BallStore& balls, const BodyStore& bodies,
                           const std::vector<Material>& materials, const std::vector<Wall>& walls,
                           const ForceSettings& s, ContactList& contacts);

// Sums the contact forces on one body's balls and gravity into its force and
// torque, and books the contacts' dissipated energy on the ball that owns them
// (side a). Reads only contact arrays and this body's state, so the integrator can
// call it body by body in its own parallel loop (no pass, no barrier of its own).
void gather_body_force(Index body, const ContactList& ball_contacts,
                       const ContactList& wall_contacts, const Vec3& gravity, BallStore& balls,
                       BodyStore& bodies);

// Velocity of a body's material point at world position p (half-step velocities).
inline Vec3 point_velocity(const BodyStore& bodies, Index body, const Vec3& p) {
  return bodies.velocity[body] + bodies.angular_velocity[body].cross(p - bodies.position[body]);
}

}  // namespace ballast
