// Simulation's checkpoint: the field lists of the engine's state (engine/state_io.hpp).
// Each list names every field of its type except those said otherwise; one list
// writes and reads. Keep them complete when a type gains a field: the resume tests
// (tests/test_checkpoint.cpp) compare the state hash of a resumed run with an
// uninterrupted one's.
#include "engine/contact_list.hpp"
#include "engine/simulation.hpp"
#include "engine/state_io.hpp"
#include "engine/store_fields.hpp"

namespace ballast {

template <>
struct Bytewise<Wrench> : std::true_type {};

template <class Io>
void state_fields(Io& io, Wall& w) {
  io(w.name, w.shape, w.point, w.normal, w.lo, w.hi, w.edge_radius, w.material, w.motion,
     w.velocity, w.displacement);
}

// Not target_force: a function, which the scene sets again.
template <class Io>
void state_fields(Io& io, Servo& s) {
  io(s.walls, s.axis, s.gain, s.max_speed, s.measured_force, s.target_now, s.speed);
}

// Not log: a stream of the process that runs it.
template <class Io>
void state_fields(Io& io, SimulationSettings& s) {
  io(s.domain_lo, s.domain_hi, s.gravity, s.local_damping, s.damping_ratio, s.fixed_dt, s.dt_safety,
     s.strict_timestep, s.skin, s.max_speed, s.contact_law, s.rotation, s.sphere_fast_path,
     s.skip_far_candidates, s.adaptive_rebuild, s.simd_lanes, s.energy_ledger);
}

template <class Io>
void ContactList::state_fields(Io& io) {
  io(a, b, shear_force, b_wrench, normal_force, slip_total, viscous_total, active, gap_at_build,
     a_first, touching_first, b_first, b_contact, live_cover, live, live_a, live_a_end, live_b,
     live_b_end, flat_c, flat_a, flat_first, flat_live_current, history_);
}

// Not the cell list (made afresh at each build), the pair table (derived from the
// materials and walls: marked stale, remade before the next force pass), the thread
// shares and the phase timers.
template <class Io>
void Simulation::state_fields(Io& io) {
  std::ostream* const log = settings_.log;
  io(settings_);
  settings_.log = log;
  io(materials_, balls_, bodies_, walls_, servos_, law_, ball_contacts_, wall_contacts_, a_side_,
     reference_positions_, wall_reference_, wall_force_, wall_last_move_, wall_force_at_move_,
     wall_forces_summed_, wall_work_, full_radius_, full_offset_, size_scale_, scale_at_build_,
     max_full_radius_, estimate_, time_, dt_, skin_, max_radius_, shift_since_build_, steps_,
     builds_, early_builds_, rebuild_policy_, prepared_, friction_, needs_rebuild_, all_spheres_,
     kernel_lanes_);
  if constexpr (Io::kReading) pairs_stale_ = true;
}

void Simulation::save_state(StateWriter& out) const {
  const_cast<Simulation*>(this)->state_fields(out);
}

void Simulation::load_state(StateReader& in) {
  state_fields(in);
}

}  // namespace ballast
