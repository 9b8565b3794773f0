#include "engine/forces.hpp"

#include <cmath>
#include <cstdint>

#include <omp.h>

#include "engine/contact_laws.hpp"
#include "engine/sphere_kernel.hpp"
#include "engine/sphere_planes.hpp"
#include "engine/work_split.hpp"

namespace ballast {

namespace {

// Raw pointers to the arrays the pass reads and writes, taken once per pass. Reached
// through the containers, every store into a contact's `active` byte (a char type,
// which may alias anything) made the compiler reload the data pointer of every
// vector the next contact reads.
struct BallView {
  const Vec3* position;
  const double* radius;
  const Index* body;
  const Index* material;
};

struct BodyView {
  const Vec3* position;
  const Vec3* velocity;
  const Vec3* angular_velocity;
  const double* mass;
  const std::uint8_t* is_sphere;
};

struct ContactView {
  const Index* b;
  const Index* a_first;
  const Index* live_a;      // ball–ball lists only
  const Index* live_a_end;  // ball–ball lists only
  Vec3* shear_force;        // null in a frictionless scene
  Wrench* b_wrench;
  double* normal_force;
  double* slip_total;
  double* viscous_total;
  std::uint8_t* active;
};

BallView view(const BallStore& s) {
  return {s.position.data(), s.radius.data(), s.body.data(), s.material.data()};
}
BodyView view(const BodyStore& s) {
  return {s.position.data(), s.velocity.data(), s.angular_velocity.data(), s.mass.data(),
          s.is_sphere.data()};
}
ContactView view(ContactList& c) {
  return {c.b.data(),
          c.a_first.data(),
          c.live_a.data(),
          c.live_a_end.data(),
          c.shear_force.data(),
          c.b_wrench.data(),
          c.normal_force.data(),
          c.slip_total.data(),
          c.viscous_total.data(),
          c.active.data()};
}

// A contact whose entities no longer overlap: PFC drops its shear force. Its b-side
// wrench goes to zero so that the gather may add the contact blindly.
template <bool kFriction>
[[gnu::always_inline]] inline void open_contact(const ContactView& cl, Index c) {
  if (!cl.active[c]) return;
  cl.active[c] = 0;
  cl.b_wrench[c] = Wrench{Vec3::Zero(), Vec3::Zero()};
  cl.normal_force[c] = 0.0;
  if constexpr (kFriction) cl.shear_force[c].setZero();
}

// Bookkeeping every touching contact does: flags, elastic normal force, energy.
template <bool kDamped>
[[gnu::always_inline]] inline void record(const ContactView& cl, Index c, const ContactResult& r,
                                          bool ledger) {
  cl.active[c] = 1;
  cl.normal_force[c] = r.normal_force;
  if (!ledger) return;
  // Slip work is zero unless the contact slides, which is rare once a bed settles.
  if (r.slip_work != 0.0) cl.slip_total[c] += r.slip_work;
  if constexpr (kDamped) cl.viscous_total[c] += r.viscous_work;
}

[[gnu::always_inline]] inline V3 velocity_at(const BodyView& bodies, Index b, const V3& arm) {
  return load(bodies.velocity[b]) + cross(load(bodies.angular_velocity[b]), arm);
}

// The law's force on one contact whose geometry and velocity `st` holds, with the
// contact's shear history in and out and its bookkeeping recorded.
template <class Law, bool kFriction, bool kDamped>
[[gnu::always_inline]] inline ContactResult evaluate(const ContactView& cl, Index c,
                                                     ContactState& st, const PairProperties& pp,
                                                     const ForceSettings& s) {
  st.damping_ratio = s.damping_ratio;
  st.dt = s.dt;
  V3 hist{0.0, 0.0, 0.0};
  if constexpr (kFriction) hist = load(cl.shear_force[c]);
  const ContactResult r = Law::template force<kFriction, kDamped>(st, pp, hist);
  if constexpr (kFriction) store(cl.shear_force[c], hist);
  record<kDamped>(cl, c, r, s.ledger);
  return r;
}

// Ball–ball contact c, seen from its side a (ball i). Adds the wrench on i to
// (f, t) and stores the wrench on b. kSpheres: every body is one ball and ball k
// is body k (ForceSettings::all_spheres), so neither the owners nor the sphere
// flags are read and the clump path is not compiled in.
template <class Law, bool kFriction, bool kDamped, bool kSpheres>
[[gnu::always_inline]] inline void ball_ball(const BallView& balls, const BodyView& bodies,
                                             const PairTable& pairs, const ForceSettings& s,
                                             const ContactView& cl, Index c, Index i, const V3& xi,
                                             double ri, V3& f, V3& t) {
  const Index j = cl.b[c];
  const V3 xj = load(balls.position[j]);
  const V3 d = xi - xj;
  const double rj = balls.radius[j];
  const double dist2 = dot(d, d);
  const double reach = ri + rj;
  if (dist2 >= reach * reach) {
    open_contact<kFriction>(cl, c);
    return;
  }
  const double dist = std::sqrt(dist2);
  const V3 normal = (1.0 / dist) * d;  // from j towards i
  const double overlap = reach - dist;
  const Index bi = kSpheres ? i : balls.body[i], bj = kSpheres ? j : balls.body[j];
  const PairProperties& pp = pairs.balls(balls.material[i], balls.material[j]);
  ContactState st;
  st.overlap = overlap;
  st.normal = normal;
  if constexpr (Law::kUsesRadius) st.radius = ri * rj / (ri + rj);
  if constexpr (kDamped)
    st.m_eff = bodies.mass[bi] * bodies.mass[bj] / (bodies.mass[bi] + bodies.mass[bj]);
  // The contact point sits mid-overlap: li from i's centre, lj from j's.
  const double li = ri - 0.5 * overlap, lj = rj - 0.5 * overlap;
  if (kSpheres || (bodies.is_sphere[bi] && bodies.is_sphere[bj])) {
    if constexpr (!kFriction) {
      // Two frictionless spheres: the force lies along the normal, through both
      // centres. It exerts no torque, and the spin velocity is normal to the normal,
      // so the dashpot (which reads vrel·n) does not see it. Neither is computed: the
      // torque is exactly zero instead of the roundoff of n × (Fn·n), and a sphere's
      // spin does not change (no rotation of frictionless spheres to integrate).
      st.vrel = load(bodies.velocity[bi]) - load(bodies.velocity[bj]);
      const ContactResult r = evaluate<Law, kFriction, kDamped>(cl, c, st, pp, s);
      f += r.force;
      store(cl.b_wrench[c].force, -r.force);
      store(cl.b_wrench[c].torque, V3{0.0, 0.0, 0.0});
      return;
    }
    // Two spheres: both lever arms lie along the normal (−li·n and +lj·n), so one
    // cross product gives the relative spin velocity and one both moments.
    st.vrel = (load(bodies.velocity[bi]) - load(bodies.velocity[bj])) -
              cross(li * load(bodies.angular_velocity[bi]) + lj * load(bodies.angular_velocity[bj]),
                    normal);
    const ContactResult r = evaluate<Law, kFriction, kDamped>(cl, c, st, pp, s);
    const V3 nxf = cross(normal, r.force);
    f += r.force;
    t += (-li) * nxf;
    store(cl.b_wrench[c].force, -r.force);
    store(cl.b_wrench[c].torque, (-lj) * nxf);
    return;
  }
  if constexpr (!kSpheres) {
    // A clump's ball: lever arms from each body's centre of mass to the contact point.
    const V3 p = xj + lj * normal;
    const V3 arm_i = p - load(bodies.position[bi]), arm_j = p - load(bodies.position[bj]);
    st.vrel = velocity_at(bodies, bi, arm_i) - velocity_at(bodies, bj, arm_j);
    const ContactResult r = evaluate<Law, kFriction, kDamped>(cl, c, st, pp, s);
    f += r.force;
    t += cross(arm_i, r.force);
    const V3 minus = -r.force;
    store(cl.b_wrench[c].force, minus);
    store(cl.b_wrench[c].torque, cross(arm_j, minus));
  }
}

// Ball–wall contact c of ball i. Adds the wrench on i to (f, t) and stores the force
// on the wall.
template <class Law, bool kFriction, bool kDamped, bool kSpheres>
[[gnu::always_inline]] inline void ball_wall(const BallView& balls, const BodyView& bodies,
                                             const PairTable& pairs, const std::vector<Wall>& walls,
                                             const ForceSettings& s, const ContactView& cl, Index c,
                                             Index i, const V3& x, double r, V3& f, V3& t) {
  const Wall& w = walls[cl.b[c]];
  double overlap;
  V3 normal, point;
  if (w.shape == WallShape::Plane) {  // the common case, inlined (touch_wall's formula)
    normal = load(w.normal);
    const double sd = dot(normal, x - load(w.point));  // signed distance of the centre
    overlap = r - sd;
    point = x - sd * normal;
  } else {
    const WallTouch touch = touch_wall(w, balls.position[i], r);
    overlap = touch.overlap;
    normal = load(touch.normal);
    point = load(touch.point);
  }
  if (overlap <= 0.0) {
    open_contact<kFriction>(cl, c);
    return;
  }
  const Index bi = kSpheres ? i : balls.body[i];
  ContactState st;
  st.overlap = overlap;
  st.normal = normal;
  if constexpr (Law::kUsesRadius) st.radius = r;
  if constexpr (kDamped) st.m_eff = bodies.mass[bi];
  const PairProperties& pp = pairs.wall(balls.material[i], cl.b[c]);
  // A frictionless sphere: the force passes through its centre (ball_ball says why
  // neither spin nor torque is computed).
  if (!kFriction && (kSpheres || bodies.is_sphere[bi])) {
    st.vrel = load(bodies.velocity[bi]) - load(w.velocity);
    const ContactResult res = evaluate<Law, kFriction, kDamped>(cl, c, st, pp, s);
    f += res.force;
    store(cl.b_wrench[c].force, -res.force);
    return;
  }
  const V3 arm = point - load(bodies.position[bi]);
  st.vrel = velocity_at(bodies, bi, arm) - load(w.velocity);
  const ContactResult res = evaluate<Law, kFriction, kDamped>(cl, c, st, pp, s);
  f += res.force;
  t += cross(arm, res.force);
  store(cl.b_wrench[c].force, -res.force);
}

// A sphere scene's share [lo, hi) in SIMD lanes: the kernel sets each ball's side-a
// wrench to its ball–ball sum, then its wall contacts add to it, as in the scalar
// pass's order (ball–ball contacts, then walls).
template <bool kFriction>
void sphere_pass_simd(const BallStore& ball_store, const BodyStore& body_store,
                      const PairTable& pairs, const std::vector<Wall>& walls,
                      const ForceSettings& s, ContactList& bc_list, ContactList& wc_list,
                      std::vector<Wrench>& a_side_store, Index lo, Index hi) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Wrench) == 6 * sizeof(double));
  static_assert(sizeof(PairProperties) == 3 * sizeof(double) && sizeof(Index) == 4);
  SphereKernelView k;
  k.position = flat(ball_store.position);
  k.radius = ball_store.radius.data();
  k.velocity = flat(body_store.velocity);
  k.angular_velocity = flat(body_store.angular_velocity);
  k.material = ball_store.material.data();
  k.pair = &pairs.balls(0, 0).normal;
  k.materials = pairs.ball_materials();
  k.dt = s.dt;
  k.b = bc_list.b.data();
  k.flat_c = bc_list.flat_c.data();
  k.flat_a = bc_list.flat_a.data();
  k.flat_first = bc_list.flat_first.data();
  k.shear_force = kFriction ? flat(bc_list.shear_force) : nullptr;
  k.b_wrench = bc_list.b_wrench.empty() ? nullptr : bc_list.b_wrench.data()->force.data();
  k.normal_force = bc_list.normal_force.data();
  k.slip_total = s.ledger ? bc_list.slip_total.data() : nullptr;
  k.active = bc_list.active.data();
  k.a_side = a_side_store.empty() ? nullptr : a_side_store.data()->force.data();
  sphere_kernel_ball_ball(k, lo, hi, s.sphere_kernel_lanes);
  if (wc_list.size() == 0) return;
  const Index* const wall_a = wc_list.a.data();
  const Index first = wc_list.a_first[lo], last = wc_list.a_first[hi];
  // The plane walls' candidates go through the kernel, then the others' (the sleeper's
  // box) through the loop below (sphere_planes.hpp says when that keeps the order).
  const PlaneTable* const planes = s.planes;
  const bool planes_in_lanes = planes != nullptr && planes->planes_in_lanes;
  if (planes_in_lanes) {
    const SpherePlaneView p = sphere_plane_view(k, *planes, pairs, wc_list, kFriction, s.ledger);
    sphere_kernel_ball_plane(p, first, last, s.sphere_kernel_lanes);
    if (!planes->other_shapes) return;
  }
  const BallView balls = view(ball_store);
  const BodyView bodies = view(body_store);
  const ContactView wc = view(wc_list);
  // One loop over the share's wall candidates, not over its balls: most balls touch
  // no wall, and a loop per ball that mostly runs no iteration mispredicts.
  Wrench* const a_side = a_side_store.data();
  const Index* const wall_b = wc_list.b.data();
  for (Index c = first; c < last; ++c) {
    if (planes_in_lanes && planes->is_plane[wall_b[c]]) continue;
    const Index i = wall_a[c];
    V3 f = load(a_side[i].force), t = load(a_side[i].torque);
    ball_wall<LinearLaw, kFriction, false, true>(balls, bodies, pairs, walls, s, wc, c, i,
                                                 load(balls.position[i]), balls.radius[i], f, t);
    store(a_side[i].force, f);
    store(a_side[i].torque, t);
  }
}

template <class Law, bool kFriction, bool kDamped, bool kSpheres>
void contact_pass(const BallStore& ball_store, const BodyStore& body_store, const PairTable& pairs,
                  const std::vector<Wall>& walls, const ForceSettings& s, ContactList& bc_list,
                  ContactList& wc_list, std::vector<Wrench>& a_side_store) {
  const bool has_walls = wc_list.size() > 0;
  const BallView balls = view(ball_store);
  const BodyView bodies = view(body_store);
  const ContactView bc = view(bc_list), wc = view(wc_list);
  Wrench* const a_side = a_side_store.data();
  const Index n_bodies = body_store.size(), n_balls = ball_store.size();
  const Index* const first_ball = body_store.first_ball.data();
  // Body b's balls are [ball_start(b), ball_start(b + 1)): contiguous, in body order.
  const auto ball_start = [&](Index b) -> Index {
    if constexpr (kSpheres) return b;
    return b < n_bodies ? first_ball[b] : n_balls;
  };
  // Each thread takes a share of bodies of about the same cost (work_split.hpp), in
  // units of a ball's bookkeeping: a candidate skipped 1, a wall candidate 4, a
  // contact touching at the build 16 (about their instruction counts). A clump bed
  // has 19 candidates per touching contact, spread evenly, while its touching
  // contacts crowd the base: counted by candidates, one thread waited at the barrier.
  const Index* const touching_first = bc_list.touching_first.data();
  const auto [lo, hi] = balanced_range(
      n_bodies,
      [&](Index b) {
        const Index k = ball_start(b);
        return 16L * touching_first[k] + bc.a_first[k] + 4L * (has_walls ? wc.a_first[k] : 0) +
               2L * k;
      },
      s.split);
  if (s.refresh_live) bc_list.refresh_live_a(ball_start(lo), ball_start(hi));
  // The kernel evaluates the linear law only (LinearLaw::kSphereKernel): a scene of
  // another law never reaches it, whatever the caller set.
  if constexpr (kSpheres && !kDamped && Law::kSphereKernel) {
    if (s.sphere_kernel_lanes > 0) {
      sphere_pass_simd<kFriction>(ball_store, body_store, pairs, walls, s, bc_list, wc_list,
                                  a_side_store, lo, hi);
      return;
    }
  }
  for (Index body = lo; body < hi; ++body) {
    // One wrench per body, summed in registers over all its balls' side-a contacts:
    // a clump's balls mostly touch nothing, and a store and a reload of 48 bytes per
    // ball (3 MB a step in a Sample 2 bed) cost more than their contacts.
    V3 f{0.0, 0.0, 0.0}, t{0.0, 0.0, 0.0};
    const Index end = ball_start(body + 1);
    for (Index i = ball_start(body); i < end; ++i) {
      const V3 x = load(balls.position[i]);
      const double r = balls.radius[i];
      // The live candidates only: one left off is a far candidate that was not
      // touching and still is not, with nothing to evaluate or clear.
      for (Index e = bc.a_first[i]; e < bc.live_a_end[i]; ++e)
        ball_ball<Law, kFriction, kDamped, kSpheres>(balls, bodies, pairs, s, bc, bc.live_a[e], i,
                                                     x, r, f, t);
      if (has_walls)
        for (Index c = wc.a_first[i]; c < wc.a_first[i + 1]; ++c)
          ball_wall<Law, kFriction, kDamped, kSpheres>(balls, bodies, pairs, walls, s, wc, c, i, x,
                                                       r, f, t);
    }
    store(a_side[body].force, f);
    store(a_side[body].torque, t);
  }
}

template <class Law, bool kFriction, bool kDamped>
void contact_pass_for(const BallStore& balls, const BodyStore& bodies, const PairTable& pairs,
                      const std::vector<Wall>& walls, const ForceSettings& s, ContactList& bc,
                      ContactList& wc, std::vector<Wrench>& a_side) {
  if (s.all_spheres)
    contact_pass<Law, kFriction, kDamped, true>(balls, bodies, pairs, walls, s, bc, wc, a_side);
  else
    contact_pass<Law, kFriction, kDamped, false>(balls, bodies, pairs, walls, s, bc, wc, a_side);
}

}  // namespace

// One instantiation per law and combination of friction, dashpots and sphere-only
// scene, so that a scene pays for none of them it does not use, not even a branch per
// contact.
void compute_contacts(const BallStore& balls, const BodyStore& bodies, const PairTable& pairs,
                      const std::vector<Wall>& walls, const ForceSettings& s,
                      ContactList& ball_contacts, ContactList& wall_contacts,
                      std::vector<Wrench>& a_side) {
  const bool damped = s.damping_ratio > 0.0;
  with_contact_law(s.law, [&](auto law) {
    using Law = decltype(law);
    if (s.friction && damped)
      contact_pass_for<Law, true, true>(balls, bodies, pairs, walls, s, ball_contacts,
                                        wall_contacts, a_side);
    else if (s.friction)
      contact_pass_for<Law, true, false>(balls, bodies, pairs, walls, s, ball_contacts,
                                         wall_contacts, a_side);
    else if (damped)
      contact_pass_for<Law, false, true>(balls, bodies, pairs, walls, s, ball_contacts,
                                         wall_contacts, a_side);
    else
      contact_pass_for<Law, false, false>(balls, bodies, pairs, walls, s, ball_contacts,
                                          wall_contacts, a_side);
  });
}

}  // namespace ballast
