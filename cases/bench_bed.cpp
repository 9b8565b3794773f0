#include "cases/bench_bed.hpp"

#include "cases/packing_bodies.hpp"

namespace ballast {

Simulation make_bench_bed(const Packing& packing, const BenchBedOptions& o) {
  SimulationSettings s;
  // Room for every body beside the walls, and twice the box height above: a ball
  // that leaves it has been thrown out of the bed, and the run says so.
  const double room = 2.0 * packing_body_size(packing);
  s.domain_lo = -Vec3::Constant(room);
  s.domain_hi = Vec3(o.length, o.width, 2.0 * o.height) + Vec3::Constant(room);
  s.gravity = Vec3(0.0, 0.0, -o.gravity);
  s.local_damping = o.local_damping;
  s.damping_ratio = 0.0;
  s.fixed_dt = o.dt;
  s.rotation = o.rotation;
  s.skip_far_candidates = o.skip_far_candidates;
  s.simd_lanes = o.simd_lanes;
  s.energy_ledger = o.energy_ledger;
  s.log = o.log;
  Simulation sim(s);
  const double k = entity_stiffness_for_contact(o.contact_stiffness);
  const Material m{k, k, o.friction};
  const Index mat = sim.add_material(m);
  for (const Wall& w : box_container(Vec3::Zero(), Vec3(o.length, o.width, o.height), m, m,
                                     /*open_top=*/true))
    sim.add_wall(w);
  // The nominal diameter only matters to mass mode "paper"; the paper's 36.25 mm.
  add_packing(sim, packing, {{o.mass_mode, o.density, 0.005}, 0.03625}, mat);
  if (!o.keep_file_order) {
    const SpatialOrder order = sim.sort_bodies_spatially();
    if (o.log) *o.log << describe(order) << "\n";
  }
  return sim;
}

namespace {

void add_contacts(const ContactList& cl, ContactForceMeans& out) {
  const bool shear = cl.has_history();
  for (Index c = 0; c < cl.size(); ++c) {
    if (!cl.active[c]) continue;
    ++out.count;
    out.normal += cl.normal_force[c];
    if (shear) out.tangential += cl.shear_force[c].norm();
  }
}

// Sums to means, divided once after a fixed-order sum.
void to_means(ContactForceMeans& m) {
  if (m.count == 0) return;
  m.normal /= double(m.count);
  m.tangential /= double(m.count);
}

}  // namespace

BenchBedPhysics measure_bench_bed(const Simulation& sim) {
  BenchBedPhysics p;
  add_contacts(sim.ball_contacts(), p.ball_ball);
  add_contacts(sim.wall_contacts(), p.ball_wall);
  add_contacts(sim.ball_contacts(), p.all);
  add_contacts(sim.wall_contacts(), p.all);
  for (ContactForceMeans* m : {&p.ball_ball, &p.ball_wall, &p.all}) to_means(*m);
  const EnergyBudget e = sim.energy();
  p.kinetic_translational = e.kinetic_translational;
  p.kinetic_rotational = e.kinetic_rotational;
  return p;
}

}  // namespace ballast
