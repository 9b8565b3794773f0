#include "engine/diagnostics.hpp"

#include <algorithm>

#include "engine/contact_laws.hpp"

namespace ballast {

namespace {

// The energy stored in the springs of every touching contact, by the law's formula.
template <class Law>
double elastic_energy(const BallStore& balls, const std::vector<Material>& materials,
                      const std::vector<Wall>& walls, const ContactList& bc,
                      const ContactList& wc) {
  double e = 0.0;
  const auto shear2 = [](const ContactList& cl, Index c) {
    return cl.has_history() ? cl.shear_force[c].squaredNorm() : 0.0;
  };
  for (Index c = 0; c < bc.size(); ++c) {
    if (!bc.active[c]) continue;
    const Index a = bc.a[c], b = bc.b[c];
    const PairProperties p = Law::mix(materials[balls.material[a]], materials[balls.material[b]]);
    const double ra = balls.radius[a], rb = balls.radius[b];
    e += Law::elastic_energy(p, ra * rb / (ra + rb), bc.normal_force[c], shear2(bc, c));
  }
  for (Index c = 0; c < wc.size(); ++c) {
    if (!wc.active[c]) continue;
    const Index a = wc.a[c];
    const PairProperties p = Law::mix(materials[balls.material[a]], walls[wc.b[c]].material);
    e += Law::elastic_energy(p, balls.radius[a], wc.normal_force[c], shear2(wc, c));
  }
  return e;
}

}  // namespace

EnergyBudget energy_budget(const BallStore& balls, const BodyStore& bodies,
                           const std::vector<Material>& materials, const std::vector<Wall>& walls,
                           const ContactList& bc, const ContactList& wc, double wall_work,
                           int law) {
  EnergyBudget e;
  for (Index b = 0; b < bodies.size(); ++b) {
    e.kinetic_translational += 0.5 * bodies.mass[b] * bodies.velocity[b].squaredNorm();
    const Vec3 w = bodies.angular_velocity[b];
    const Vec3 w_body = bodies.is_sphere[b] ? w : bodies.orientation[b].inverse() * w;
    e.kinetic_rotational += 0.5 * w_body.dot(bodies.inertia[b].cwiseProduct(w_body));
    e.gravity_work += bodies.gravity_work[b];
    e.damping_dissipated += bodies.damping_dissipated[b];
  }
  for (Index k = 0; k < balls.size(); ++k) {
    e.friction_dissipated += balls.friction_dissipated[k];
    e.viscous_dissipated += balls.viscous_dissipated[k];
  }
  // What the live contacts have dissipated since the last rebuild (not yet flushed
  // into the ball ledger).
  for (const ContactList* cl : {&bc, &wc})
    for (Index c = 0; c < cl->size(); ++c) {
      e.friction_dissipated += cl->slip_total[c];
      e.viscous_dissipated += cl->viscous_total[c];
    }
  e.elastic = with_contact_law(
      law, [&](auto l) { return elastic_energy<decltype(l)>(balls, materials, walls, bc, wc); });
  e.wall_work = wall_work;
  return e;
}

ContactStats contact_stats(const BodyStore& bodies, const ContactList& bc, const ContactList& wc) {
  ContactStats s;
  double sum = 0.0;
  auto visit = [&](const ContactList& cl, long& count) {
    for (Index c = 0; c < cl.size(); ++c) {
      if (!cl.active[c]) continue;
      ++count;
      const double f = cl.force(c).norm();
      sum += f;
      s.max_force = std::max(s.max_force, f);
    }
  };
  visit(bc, s.ball_contacts);
  visit(wc, s.wall_contacts);
  const long total = s.ball_contacts + s.wall_contacts;
  s.mean_force = total > 0 ? sum / total : 0.0;
  s.coordination = bodies.size() > 0 ? 2.0 * s.ball_contacts / bodies.size() : 0.0;
  return s;
}

double unbalanced_force_ratio(const BodyStore& bodies, const ContactList& bc,
                              const ContactList& wc) {
  const ContactStats s = contact_stats(bodies, bc, wc);
  if (s.mean_force <= 0.0 || bodies.size() == 0) return 0.0;
  double sum = 0.0;
  for (Index b = 0; b < bodies.size(); ++b) sum += bodies.force[b].norm();
  return (sum / bodies.size()) / s.mean_force;
}

}  // namespace ballast
