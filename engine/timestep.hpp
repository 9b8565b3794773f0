// Critical timestep estimate, after PFC. For each body
//     dt_body = 1 / sqrt(k_tran/m + k_rot/I_min)
// with k_tran = Σ (kn + ks) over the body's touching contacts and
// k_rot = Σ (kn·|r×n|² + ks·|r|²), r the lever arm from the centre of mass to the
// contact point, kn and ks the contact law's tangent stiffnesses at the contact's
// overlap (contact_law.hpp). A body can always gain a contact within one step, so
// both sums are floored at one contact with a ball like its own (the law's
// floor_stiffness: for the linear law the ball's kn, ks in series with themselves). dt_critical is
// the smallest over all bodies, reduced further when contact dashpots are on. Leapfrog on a single
// spring is stable up to 2·sqrt(m/k), so the estimate keeps a margin for contacts acting together,
// like PFC's.
#pragma once

#include <vector>

#include "engine/ball_store.hpp"
#include "engine/body_store.hpp"
#include "engine/contact_list.hpp"
#include "engine/material.hpp"
#include "engine/walls.hpp"

namespace ballast {

// law: the contact law's number in ContactLaws (contact_laws.hpp); max_speed (m/s):
// the fastest a body may move, which sets the floor of a law whose stiffness grows
// with the overlap.
struct TimestepEstimate {
  double critical = 0.0;  // s
  Index limiting_body = kNoIndex;
  bool limited_by_rotation = false;
};

TimestepEstimate estimate_critical_timestep(const BallStore& balls, const BodyStore& bodies,
                                            const std::vector<Material>& materials,
                                            const std::vector<Wall>& walls,
                                            const ContactList& ball_contacts,
                                            const ContactList& wall_contacts, double damping_ratio,
                                            int law, double max_speed);

// The same estimate for one sphere of `radius` (m) and `density` (kg/m³) with its one
// floor contact, before any body exists: what a scene can know up front. A bed only
// adds contacts, so its estimate is at most this (cases/scene_bounds.cpp bounds a
// scene's steps with it). Infinite or zero where the material makes no sense.
double lone_sphere_timestep(const Material& m, double radius, double density, int law,
                            double max_speed);

}  // namespace ballast
