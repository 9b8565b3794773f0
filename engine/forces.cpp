#include "engine/forces.hpp"

#include <cmath>

#include "engine/contact_law.hpp"

namespace ballast {

namespace {

// A contact whose entities no longer overlap: PFC drops its shear force.
template <bool kFriction>
inline void open_contact(ContactList& cl, Index c) {
  if (!cl.active[c]) return;
  cl.active[c] = 0;
  cl.force[c].setZero();
  cl.normal_force[c] = 0.0;
  cl.slip_work[c] = cl.viscous_work[c] = 0.0;
  if constexpr (kFriction) cl.shear_force[c].setZero();
}

inline void store_contact(ContactList& cl, Index c, const ContactResult& r, const Vec3& point) {
  cl.active[c] = 1;
  cl.force[c] = r.force;
  cl.point[c] = point;
  cl.normal_force[c] = r.normal_force;
  cl.slip_work[c] = r.slip_work;
  cl.viscous_work[c] = r.viscous_work;
}

template <bool kFriction>
void ball_contact_loop(const BallStore& balls, const BodyStore& bodies,
                       const std::vector<Material>& materials, const ForceSettings& s,
                       ContactList& cl) {
  const Index n = cl.size();
  const bool damped = s.damping_ratio > 0.0;
  // nowait: the wall loop that follows reads only positions and velocities, which
  // no contact loop writes. The caller puts one barrier after both loops.
#pragma omp for schedule(static) nowait
  for (Index c = 0; c < n; ++c) {
    const Index i = cl.a[c], j = cl.b[c];
    const Vec3 d = balls.position[i] - balls.position[j];
    const double ri = balls.radius[i], rj = balls.radius[j];
    const double dist2 = d.squaredNorm();
    const double reach = ri + rj;
    if (dist2 >= reach * reach) {
      open_contact<kFriction>(cl, c);
      continue;
    }
    const double dist = std::sqrt(dist2);
    const Vec3 n = d / dist;  // from j towards i
    const double overlap = reach - dist;
    const Vec3 p = balls.position[j] + (rj - 0.5 * overlap) * n;
    const Index bi = balls.body[i], bj = balls.body[j];
    const Material& mi = materials[balls.material[i]];
    const Material& mj = materials[balls.material[j]];
    ContactState st;
    st.overlap = overlap;
    st.normal = n;
    st.vrel = point_velocity(bodies, bi, p) - point_velocity(bodies, bj, p);
    st.kn = series_stiffness(mi.kn, mj.kn);
    st.ks = series_stiffness(mi.ks, mj.ks);
    st.mu = contact_friction(mi.mu, mj.mu);
    st.cn = st.cs = 0.0;
    if (damped) {
      const double m_eff = bodies.mass[bi] * bodies.mass[bj] / (bodies.mass[bi] + bodies.mass[bj]);
      st.cn = dashpot_coefficient(s.damping_ratio, m_eff, st.kn);
      st.cs = dashpot_coefficient(s.damping_ratio, m_eff, st.ks);
    }
    st.dt = s.dt;
    Vec3 unused = Vec3::Zero();
    Vec3& hist = kFriction ? cl.shear_force[c] : unused;
    store_contact(cl, c, linear_contact<kFriction>(st, hist), p);
  }
}

template <bool kFriction>
void wall_contact_loop(const BallStore& balls, const BodyStore& bodies,
                       const std::vector<Material>& materials, const std::vector<Wall>& walls,
                       const ForceSettings& s, ContactList& cl) {
  const Index n = cl.size();
  const bool damped = s.damping_ratio > 0.0;
#pragma omp for schedule(static) nowait
  for (Index c = 0; c < n; ++c) {
    const Index i = cl.a[c];
    const Wall& w = walls[cl.b[c]];
    const WallTouch t = touch_wall(w, balls.position[i], balls.radius[i]);
    if (t.overlap <= 0.0) {
      open_contact<kFriction>(cl, c);
      continue;
    }
    const Index bi = balls.body[i];
    const Material& mi = materials[balls.material[i]];
    ContactState st;
    st.overlap = t.overlap;
    st.normal = t.normal;
    st.vrel = point_velocity(bodies, bi, t.point) - w.velocity;
    st.kn = series_stiffness(mi.kn, w.material.kn);
    st.ks = series_stiffness(mi.ks, w.material.ks);
    st.mu = contact_friction(mi.mu, w.material.mu);
    st.cn = st.cs = 0.0;
    if (damped) {
      st.cn = dashpot_coefficient(s.damping_ratio, bodies.mass[bi], st.kn);
      st.cs = dashpot_coefficient(s.damping_ratio, bodies.mass[bi], st.ks);
    }
    st.dt = s.dt;
    Vec3 unused = Vec3::Zero();
    Vec3& hist = kFriction ? cl.shear_force[c] : unused;
    store_contact(cl, c, linear_contact<kFriction>(st, hist), t.point);
  }
}

}  // namespace

void compute_ball_contacts(const BallStore& balls, const BodyStore& bodies,
                           const std::vector<Material>& materials, const ForceSettings& s,
                           ContactList& contacts) {
  if (s.friction)
    ball_contact_loop<true>(balls, bodies, materials, s, contacts);
  else
    ball_contact_loop<false>(balls, bodies, materials, s, contacts);
}

void compute_wall_contacts(const BallStore& balls, const BodyStore& bodies,
                           const std::vector<Material>& materials, const std::vector<Wall>& walls,
                           const ForceSettings& s, ContactList& contacts) {
  if (s.friction)
    wall_contact_loop<true>(balls, bodies, materials, walls, s, contacts);
  else
    wall_contact_loop<false>(balls, bodies, materials, walls, s, contacts);
}

void gather_body_force(Index body, const ContactList& bc, const ContactList& wc,
                       const Vec3& gravity, BallStore& balls, BodyStore& bodies) {
  const bool has_walls = wc.size() > 0;
  const Vec3 x = bodies.position[body];
  Vec3 f = bodies.mass[body] * gravity;
  Vec3 m = Vec3::Zero();
  const Index first = bodies.first_ball[body], last = first + bodies.ball_count[body];
  for (Index ball = first; ball < last; ++ball) {
    for (Index k = bc.ball_offset[ball]; k < bc.ball_offset[ball + 1]; ++k) {
      const Index e = bc.ball_entry[k];
      const Index c = e >> 1;
      if (!bc.active[c]) continue;
      const Vec3 fc = (e & 1) ? Vec3(-bc.force[c]) : bc.force[c];
      f += fc;
      m += (bc.point[c] - x).cross(fc);
      if (!(e & 1)) {
        balls.friction_dissipated[ball] += bc.slip_work[c];
        balls.viscous_dissipated[ball] += bc.viscous_work[c];
      }
    }
    if (!has_walls) continue;
    for (Index k = wc.ball_offset[ball]; k < wc.ball_offset[ball + 1]; ++k) {
      const Index c = wc.ball_entry[k] >> 1;
      if (!wc.active[c]) continue;
      f += wc.force[c];
      m += (wc.point[c] - x).cross(wc.force[c]);
      balls.friction_dissipated[ball] += wc.slip_work[c];
      balls.viscous_dissipated[ball] += wc.viscous_work[c];
    }
  }
  bodies.force[body] = f;
  bodies.torque[body] = m;
}

}  // namespace ballast
