#include "engine/state_hash.hpp"

#include <cstddef>

#include "engine/fnv1a.hpp"
#include "engine/simulation.hpp"

namespace ballast {

namespace {

// Vec3 and Quat are plain doubles, no padding: their bytes are their values.
static_assert(sizeof(Vec3) == 3 * sizeof(double));
static_assert(sizeof(Quat) == 4 * sizeof(double));
// Every field of the budget is hashed by name below: a new one must be added there.
static_assert(sizeof(EnergyBudget) == 9 * sizeof(double) &&
              offsetof(EnergyBudget, booked) == 8 * sizeof(double));

void fold_motion(Fnv1a& f, const BodyStore& bodies) {
  f.all(bodies.position);
  f.all(bodies.velocity);
  f.all(bodies.angular_velocity);
  f.all(bodies.angular_momentum);
  f.all(bodies.orientation);
  f.all(bodies.rotation);  // the box test's headline measurement
  f.all(bodies.reference_position);
}

void fold_contacts(Fnv1a& f, const ContactList& c) {
  f.all(c.a);
  f.all(c.b);
  f.all(c.shear_force);
  f.all(c.normal_force);
  f.all(c.slip_total);
  f.all(c.viscous_total);
}

}  // namespace

std::uint64_t motion_hash(const BodyStore& bodies) {
  Fnv1a f;
  fold_motion(f, bodies);
  return f.h;
}

std::uint64_t state_hash(const Simulation& sim) {
  Fnv1a f;
  fold_motion(f, sim.bodies());
  f.all(sim.bodies().force);
  f.all(sim.bodies().torque);
  // The energy ledger entry by entry, then its totals: a difference in one body's or
  // ball's share can be below the last bit of the total.
  f.all(sim.bodies().gravity_work);
  f.all(sim.bodies().damping_dissipated);
  f.all(sim.balls().friction_dissipated);
  f.all(sim.balls().viscous_dissipated);
  fold_contacts(f, sim.ball_contacts());
  fold_contacts(f, sim.wall_contacts());
  const EnergyBudget e = sim.energy();
  for (double v : {e.kinetic_translational, e.kinetic_rotational, e.elastic, e.gravity_work,
                   e.wall_work, e.friction_dissipated, e.damping_dissipated, e.viscous_dissipated})
    f.value(v);
  f.value(e.booked ? 1.0 : 0.0);
  for (const Wall& w : sim.walls()) {
    for (const Vec3* v : {&w.point, &w.normal, &w.lo, &w.hi, &w.velocity, &w.displacement})
      f.value(*v);
    f.value(w.edge_radius);
  }
  for (const Servo& s : sim.servos()) {
    f.value(s.measured_force);
    f.value(s.target_now);
    f.value(s.speed);
  }
  f.value(sim.time());
  f.value(sim.dt());
  f.value(sim.step_count());
  return f.h;
}

}  // namespace ballast
