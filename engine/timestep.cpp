#include "engine/timestep.hpp"

#include <omp.h>

#include <cmath>
#include <limits>
#include <vector>

#include "engine/contact_laws.hpp"

namespace ballast {

namespace {

struct Stiffness {
  double tran = 0.0, rot = 0.0;
  void add(double kn, double ks, const Vec3& lever, const Vec3& n) {
    tran += kn + ks;
    rot += kn * lever.cross(n).squaredNorm() + ks * lever.squaredNorm();
  }
};

// The body's contact stiffnesses, translational and rotational (about its centre),
// from the candidates that touch now, at least one contact with an identical ball.
template <class Law>
Stiffness body_stiffness(Index body, const BallStore& balls, const BodyStore& bodies,
                         const std::vector<Material>& materials, const std::vector<Wall>& walls,
                         const ContactList& bc, const ContactList& wc, double max_speed) {
  const Vec3 x = bodies.position[body];
  Stiffness k, floor;
  const Index first = bodies.first_ball[body], last = first + bodies.ball_count[body];
  for (Index ball = first; ball < last; ++ball) {
    const Material& m = materials[balls.material[ball]];
    const Vec3 px = balls.position[ball];
    const double r = balls.radius[ball];
    // Floor: one contact with an identical ball, on the far side of this ball
    // along x (a sphere's normal force then has no lever arm, as it should).
    Stiffness one;
    const ContactStiffness kf = Law::floor_stiffness(m, r, bodies.mass[body], max_speed);
    one.add(kf.kn, kf.ks, (px - x) + r * Vec3::UnitX(), Vec3::UnitX());
    floor.tran = std::max(floor.tran, one.tran);
    floor.rot = std::max(floor.rot, one.rot);
    const auto add_ball = [&](Index other) {
      const Vec3 d = px - balls.position[other];
      const double reach = r + balls.radius[other];
      if (d.squaredNorm() >= reach * reach) return;
      const double dist = d.norm();
      const Vec3 n = dist > 0.0 ? Vec3(d / dist) : d;  // Eigen's normalized(), to the bit
      const double ro = balls.radius[other];
      const ContactStiffness kc = Law::stiffness(Law::mix(m, materials[balls.material[other]]),
                                                 r * ro / (r + ro), reach - dist);
      k.add(kc.kn, kc.ks, (px - x) - r * n, n);
    };
    for (Index c = bc.a_first[ball]; c < bc.a_first[ball + 1]; ++c) add_ball(bc.b[c]);
    for (Index e = bc.b_first[ball]; e < bc.b_first[ball + 1]; ++e) add_ball(bc.a[bc.b_contact[e]]);
    for (Index c = wc.a_first[ball]; c < wc.a_first[ball + 1]; ++c) {
      const Wall& w = walls[wc.b[c]];
      const WallTouch t = touch_wall(w, px, r);
      if (t.overlap <= 0.0) continue;
      const ContactStiffness kc = Law::stiffness(Law::mix(m, w.material), r, t.overlap);
      k.add(kc.kn, kc.ks, t.point - x, t.normal);
    }
  }
  k.tran = std::max(k.tran, floor.tran);
  k.rot = std::max(k.rot, floor.rot);
  return k;
}

}  // namespace

TimestepEstimate estimate_critical_timestep(const BallStore& balls, const BodyStore& bodies,
                                            const std::vector<Material>& materials,
                                            const std::vector<Wall>& walls, const ContactList& bc,
                                            const ContactList& wc, double damping_ratio, int law,
                                            double max_speed) {
  // Every 100 steps (Simulation::kTimestepRefreshSteps), over every candidate: serial,
  // it kept the other threads waiting (about 1 % of a smoke-scale Sample 1 box test's
  // samples on two threads, docs/PERFORMANCE.md). Each thread keeps the first
  // smallest body of a contiguous range of bodies, and the ranges are combined in
  // order, so the result is the serial loop's (the first body with the smallest
  // estimate) on any number of threads.
  const Index nb = bodies.size();
  std::vector<TimestepEstimate> per_thread;
#pragma omp parallel
  {
#pragma omp single
    per_thread.resize(omp_get_num_threads());
    TimestepEstimate best;
    best.critical = std::numeric_limits<double>::infinity();
#pragma omp for schedule(static) nowait
    for (Index body = 0; body < nb; ++body) {
      const Stiffness k = with_contact_law(law, [&](auto l) {
        return body_stiffness<decltype(l)>(body, balls, bodies, materials, walls, bc, wc,
                                           max_speed);
      });
      // Translation and rotation are coupled through the shear springs (a sphere's
      // tangential contact mode has 1/m_eff = 1/m + r²/I), so the frequencies add:
      // ω² = k_tran/m + k_rot/I_min. PFC takes min(t_tran, t_rot) instead; that let
      // beds chatter at the Nyquist frequency (period-2 force flips) under local
      // damping, so we keep the stricter sum.
      const double w2_tran = k.tran / bodies.mass[body];
      const double w2_rot = k.rot / bodies.inertia[body].minCoeff();
      const double t = 1.0 / std::sqrt(w2_tran + w2_rot);
      if (t < best.critical) {
        best.critical = t;
        best.limiting_body = body;
        best.limited_by_rotation = w2_rot > w2_tran;
      }
    }
    per_thread[omp_get_thread_num()] = best;
  }
  TimestepEstimate best;
  best.critical = std::numeric_limits<double>::infinity();
  for (const TimestepEstimate& e : per_thread)
    if (e.critical < best.critical) best = e;
  // A dashpot lowers leapfrog's stability limit from 2/ω to 2/ω·(√(1+β²) − β).
  if (damping_ratio > 0.0)
    best.critical *= std::sqrt(1.0 + damping_ratio * damping_ratio) - damping_ratio;
  return best;
}

double lone_sphere_timestep(const Material& m, double radius, double density, int law,
                            double max_speed) {
  const double mass = density * 4.0 / 3.0 * kPi * radius * radius * radius;
  const ContactStiffness k = with_contact_law(
      law, [&](auto l) { return decltype(l)::floor_stiffness(m, radius, mass, max_speed); });
  // The floor contact's lever arm is the radius along its normal: kn has no moment,
  // ks·r² does, and I = (2/5)·m·r², so ω² = (kn + ks)/m + ks·r²/I = (kn + 3.5·ks)/m.
  return 1.0 / std::sqrt((k.kn + 3.5 * k.ks) / mass);
}

}  // namespace ballast
