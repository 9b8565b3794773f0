// What a run reports about itself: the energy budget, contact statistics and PFC's
// unbalanced-force ratio. All sums run serially in index order over per-body,
// per-ball or per-contact values, so they are identical for any thread count.
#pragma once

#include <limits>
#include <vector>

#include "engine/ball_store.hpp"
#include "engine/body_store.hpp"
#include "engine/contact_list.hpp"
#include "engine/material.hpp"
#include "engine/walls.hpp"

namespace ballast {

// Energies in joules. Work terms are cumulative since the start of the run.
// Balance: kinetic + elastic + friction + damping + viscous − gravity_work − wall_work
// stays equal to its initial value (the kinetic energy given at the start).
struct EnergyBudget {
  double kinetic_translational = 0.0;  // Σ ½ m v²   (half-step velocities)
  double kinetic_rotational = 0.0;     // Σ ½ ω·I ω
  double elastic = 0.0;                // Σ Fn²/(2kn) + |Fs|²/(2ks) over touching contacts
  double gravity_work = 0.0;           // work done by gravity on the bodies
  double wall_work = 0.0;              // work done by moving walls on the balls
  double friction_dissipated = 0.0;    // Coulomb slip
  double damping_dissipated = 0.0;     // PFC local damping
  double viscous_dissipated = 0.0;     // contact dashpots
  // false: the run kept no ledger (SimulationSettings::energy_ledger); the work and
  // dissipation terms are zero and the balance is unknown (NaN).
  bool booked = true;

  double kinetic() const { return kinetic_translational + kinetic_rotational; }
  double dissipated() const {
    return friction_dissipated + damping_dissipated + viscous_dissipated;
  }
  // Mechanical energy now plus all that has left, minus all that was put in.
  double balance() const {
    if (!booked) return std::numeric_limits<double>::quiet_NaN();
    return kinetic() + elastic + dissipated() - gravity_work - wall_work;
  }
  // Kinetic and elastic energy only: what is known without a ledger.
  void drop_work() {
    gravity_work = wall_work = friction_dissipated = damping_dissipated = viscous_dissipated = 0.0;
    booked = false;
  }
};

struct ContactStats {
  long ball_contacts = 0;     // touching ball–ball pairs (different bodies)
  long wall_contacts = 0;     // touching ball–wall pairs
  double coordination = 0.0;  // 2·ball_contacts / bodies
  double max_force = 0.0;     // N, largest |contact force| over both kinds
  double mean_force = 0.0;    // N, mean |contact force| over both kinds
};

EnergyBudget energy_budget(const BallStore& balls, const BodyStore& bodies,
                           const std::vector<Material>& materials, const std::vector<Wall>& walls,
                           const ContactList& ball_contacts, const ContactList& wall_contacts,
                           double wall_work, int law);

ContactStats contact_stats(const BodyStore& bodies, const ContactList& ball_contacts,
                           const ContactList& wall_contacts);

// PFC's equilibrium measure: mean |resultant force on a body| over mean |contact
// force|. Tends to 0 as the assembly comes to rest; PFC's usual target is 1e-2..1e-3.
double unbalanced_force_ratio(const BodyStore& bodies, const ContactList& ball_contacts,
                              const ContactList& wall_contacts);

}  // namespace ballast
