#include "engine/diagnostics.hpp"

#include <algorithm>

namespace ballast {

namespace {

double contact_elastic_energy(double fn, const Vec3* fs, double kn, double ks) {
  double e = kn > 0.0 ? 0.5 * fn * fn / kn : 0.0;
  if (fs && ks > 0.0) e += 0.5 * fs->squaredNorm() / ks;
  return e;
}

}  // namespace

EnergyBudget energy_budget(const BallStore& balls, const BodyStore& bodies,
                           const std::vector<Material>& materials, const std::vector<Wall>& walls,
                           const ContactList& bc, const ContactList& wc, double wall_work) {
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
  for (Index c = 0; c < bc.size(); ++c) {
    if (!bc.active[c]) continue;
    const Material& ma = materials[balls.material[bc.a[c]]];
    const Material& mb = materials[balls.material[bc.b[c]]];
    e.elastic +=
        contact_elastic_energy(bc.normal_force[c], bc.has_history() ? &bc.shear_force[c] : nullptr,
                               series_stiffness(ma.kn, mb.kn), series_stiffness(ma.ks, mb.ks));
  }
  for (Index c = 0; c < wc.size(); ++c) {
    if (!wc.active[c]) continue;
    const Material& ma = materials[balls.material[wc.a[c]]];
    const Material& mw = walls[wc.b[c]].material;
    e.elastic +=
        contact_elastic_energy(wc.normal_force[c], wc.has_history() ? &wc.shear_force[c] : nullptr,
                               series_stiffness(ma.kn, mw.kn), series_stiffness(ma.ks, mw.ks));
  }
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
