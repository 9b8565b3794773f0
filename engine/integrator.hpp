// Centred-difference (leapfrog) integration of rigid bodies, as PFC3D does it
// (paper eqs 16–17): velocities live at half steps, positions and forces at whole
// steps.
//   v(t+dt/2) = v(t−dt/2) + dt·F_d(t)/m,   x(t+dt) = x(t) + dt·v(t+dt/2)
// F_d is the resultant after PFC local damping, applied per component:
//   F_d,i = F_i − α·|F_i|·sign(v_i)            (same for moments with ω_i)
//
// Rotation. A sphere has an isotropic inertia, so ω += dt·M/I with no frame
// changes and no orientation to keep (its accumulated rotation vector Σω·dt is all
// the paper measures). A clump turns by one of the two integrators of
// rigid_rotation.hpp (`pfc`: eq 17 without the gyroscopic term; `full`: Euler's
// equations) and its balls are re-placed from the new orientation.
#pragma once

#include "engine/ball_store.hpp"
#include "engine/body_store.hpp"
#include "engine/contact_list.hpp"
#include "engine/rigid_rotation.hpp"
#include "engine/timed_split.hpp"

namespace ballast {

struct IntegratorSettings {
  double dt = 0.0;              // s
  double local_damping = 0.7;   // α, PFC's default
  Vec3 gravity = Vec3::Zero();  // m/s², only for the energy ledger (force already has m·g)
  double max_speed = 100.0;     // m/s; faster is treated as a blow-up
  RotationIntegrator rotation = RotationIntegrator::kPfc;  // for clumps
  bool all_spheres = false;  // every body is one ball and ball k is body k
  bool ledger = true;        // book gravity work and damping (SimulationSettings::energy_ledger)
  // > 0: a sphere scene's leapfrog runs in SIMD lanes, that many spheres a pass
  // (sphere_kernel.hpp; the same bits as one at a time).
  int sphere_kernel_lanes = 0;
  // The force pass of this step remade the live marks: remake each body's live
  // side-b list before gathering it (ForceSettings::refresh_live).
  bool refresh_live = false;
  // Thread shares that follow measured time (timed_split.hpp); null: equal shares.
  // The caller times each thread's pass, records and updates it.
  TimedSplit* split = nullptr;
};

struct IntegrationReport {
  double max_ball_shift2 = 0.0;  // m², largest squared ball move since `reference`
  Index bad_body = kNoIndex;     // lowest-index body that went non-finite or too fast
  bool bad_is_nan = false;       // true: non-finite; false: over max_speed
};

// Gathers each body's contact forces (forces.hpp: its a-side sum `a_side`, one per body, and
// the b-side wrenches of `ball_contacts`), advances it by one step and re-places its
// balls. `reference` holds ball positions at the last neighbour build, for the skin
// criterion. Each thread takes a share of the bodies (work_split.hpp): call it from
// inside a parallel region (all threads) or outside one (serial). `report` must be
// shared by the threads and start as IntegrationReport{}; it is complete once every
// thread has returned (at the end of the parallel region: no barrier here), except
// bad_is_nan, which finish_report() fills in.
void integrate(const IntegratorSettings& s, ContactList& ball_contacts,
               const std::vector<Wrench>& a_side, const std::vector<Vec3>& reference,
               BodyStore& bodies, BallStore& balls, IntegrationReport& report);

// Serially, after integrate(): says whether the bad body, if any, went non-finite.
void finish_report(const BodyStore& bodies, IntegrationReport& report);

}  // namespace ballast
