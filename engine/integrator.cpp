#include "engine/integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include <omp.h>

#include "engine/forces.hpp"
#include "engine/sphere_kernel.hpp"
#include "engine/v3.hpp"
#include "engine/work_split.hpp"

namespace ballast {

namespace {

// PFC local damping on one component: f − α·|f|·sign(v), written as selects (no
// sign() product) so that the compiler emits no branches.
[[gnu::always_inline]] inline double local_damp(double f, double v, double alpha) {
  const double cut = alpha * std::abs(f);
  return v > 0.0 ? f - cut : (v < 0.0 ? f + cut : f);
}
[[gnu::always_inline]] inline V3 local_damp(const V3& f, const V3& v, double alpha) {
  return {local_damp(f.x, v.x, alpha), local_damp(f.y, v.y, alpha), local_damp(f.z, v.z, alpha)};
}

// Calls f(std::bool_constant<a>{}, std::bool_constant<b>{}): two run-time flags as
// template arguments.
template <class F>
void with_flags(bool a, bool b, F&& f) {
  const auto second = [&](auto first) {
    b ? f(first, std::true_type{}) : f(first, std::false_type{});
  };
  a ? second(std::true_type{}) : second(std::false_type{});
}

struct ThreadReport {
  double shift2 = 0.0;
  Index bad = std::numeric_limits<Index>::max();
};

// One body, one step, once gather_body_force has stored its resultant force and
// torque. kDamped: local damping on (α > 0), a template argument so that undamped
// scenes carry no test for it per body. kLedger: the energy ledger is kept
// (IntegratorSettings::ledger). kSpheres: a scene of spheres only
// (IntegratorSettings::all_spheres), where body b is ball b and the clump path is
// not compiled in; it also places the ball. In a clump scene the caller places the
// balls afterwards (place_balls). The sphere kernel (sphere_kernel.hpp) does the
// same operations for several spheres at once.
template <bool kDamped, bool kLedger, bool kSpheres>
[[gnu::always_inline]] inline void update_body(const IntegratorSettings& s,
                                               const std::vector<Vec3>& reference,
                                               BodyStore& bodies, BallStore& balls, Index b,
                                               ThreadReport& out) {
  const double dt = s.dt, alpha = s.local_damping;
  const V3 f_raw = load(bodies.force[b]), m_raw = load(bodies.torque[b]);
  const V3 v_old = load(bodies.velocity[b]), w_old = load(bodies.angular_velocity[b]);
  const V3 f = kDamped ? local_damp(f_raw, v_old, alpha) : f_raw;
  const V3 torque = kDamped ? local_damp(m_raw, w_old, alpha) : m_raw;

  const V3 v_new = v_old + (dt * bodies.inv_mass[b]) * f;
  const V3 x_new = load(bodies.position[b]) + dt * v_new;
  store(bodies.velocity[b], v_new);
  store(bodies.position[b], x_new);

  V3 w_new;
  const bool sphere = kSpheres || bodies.is_sphere[b];
  if (sphere) {
    w_new = w_old + (dt * bodies.inv_inertia[b][0]) * torque;
  } else if constexpr (!kSpheres) {
    Vec3 t;
    store(t, torque);
    RotationState rs{bodies.orientation[b], bodies.angular_velocity[b], bodies.angular_momentum[b]};
    if (s.rotation == RotationIntegrator::kFull)
      rotate_full(rs, t, bodies.inv_inertia[b], dt);
    else
      rotate_pfc(rs, t, bodies.inv_inertia[b], dt);
    bodies.orientation[b] = rs.orientation;
    bodies.angular_momentum[b] = rs.angular_momentum;
    w_new = load(rs.angular_velocity);
  }
  store(bodies.angular_velocity[b], w_new);
  store(bodies.rotation[b], load(bodies.rotation[b]) + dt * w_new);

  // Energy ledger with mid-step velocities, so it matches the kinetic energy
  // change of the half-step velocities exactly: ΔKE = F·(v_old + v_new)/2·dt.
  if constexpr (kLedger) {
    const V3 v_mid = 0.5 * (v_old + v_new), w_mid = 0.5 * (w_old + w_new);
    bodies.gravity_work[b] += dt * bodies.mass[b] * dot(load(s.gravity), v_mid);
    if constexpr (kDamped)
      bodies.damping_dissipated[b] -= dt * (dot(f - f_raw, v_mid) + dot(torque - m_raw, w_mid));
  }

  // Re-place the ball and measure how far it moved since the neighbour build.
  if constexpr (kSpheres) {
    store(balls.position[b], x_new);
    const V3 moved = x_new - load(reference[b]);
    out.shift2 = std::max(out.shift2, dot(moved, moved));
  }

  const double speed2 = dot(v_new, v_new);
  if (!std::isfinite(speed2) || !std::isfinite(dot(w_new, w_new)) ||
      speed2 > s.max_speed * s.max_speed)
    out.bad = std::min(out.bad, b);
}

// A clump scene: re-places body b's balls from its new position and orientation
// (a sphere body's one ball takes its position) and measures how far they moved
// since the neighbour build.
inline void place_balls(const std::vector<Vec3>& reference, const BodyStore& bodies,
                        BallStore& balls, Index b, ThreadReport& out) {
  const Index first = bodies.first_ball[b];
  if (bodies.is_sphere[b]) {
    const V3 x = load(bodies.position[b]);
    store(balls.position[first], x);
    const V3 moved = x - load(reference[first]);
    out.shift2 = std::max(out.shift2, dot(moved, moved));
    return;
  }
  const Index last = first + bodies.ball_count[b];
  const Mat3 rot = bodies.orientation[b].toRotationMatrix();
  for (Index k = first; k < last; ++k) {
    balls.position[k] = bodies.position[b] + rot * balls.offset[k];
    out.shift2 = std::max(out.shift2, (balls.position[k] - reference[k]).squaredNorm());
  }
}

// Bodies per block of a clump scene's integration. Each body's own work is one long
// chain of dependent operations: the gather's loads of contact wrenches from all
// over the list, then rotate_pfc's matrix products, square roots, divisions and
// sincos. Done body after body, the gather, the rotation and the ball placement of
// one body filled the out-of-order window and the next body's chain started when
// the last one ended; done a block at a time, one kind of work per loop, the chains
// of neighbouring bodies overlap. Same operations per body, so the same bits. On the
// Sample 1 bench bed, one thread, the integration fell from 0.79 to 0.64 of the force
// pass's time with the box tests' numerics, and from 0.96 to 0.76 with the
// benchmark's (docs/PERFORMANCE.md, "What bought what"). The size is not critical; 16 bodies'
// balls (about 160 in Sample 1) stay in L1 between the loops.
constexpr Index kBodyBlock = 16;

template <bool kDamped, bool kLedger, bool kSpheres>
void step_bodies(const IntegratorSettings& s, ContactList& bc, const std::vector<Wrench>& a_side,
                 const std::vector<Vec3>& reference, BodyStore& bodies, BallStore& balls, Index lo,
                 Index hi, ThreadReport& out) {
  // A local report, so that its running max can stay in a register: through `out`
  // it lived in memory, since the stores into ball positions may alias it, and
  // every ball paid a load, a max and a store in one chain (`perf annotate` of a
  // smoke-scale Sample 2 run put 9 % of the integrator's samples on that store).
  // Same bits; no speed difference this host's noise can resolve.
  ThreadReport mine = out;
  if constexpr (kSpheres) {
    for (Index b = lo; b < hi; ++b) {
      gather_body_force<true>(b, bc, a_side, s.gravity, bodies, s.refresh_live);
      update_body<kDamped, kLedger, true>(s, reference, bodies, balls, b, mine);
    }
  } else {
    for (Index b0 = lo; b0 < hi; b0 += kBodyBlock) {
      const Index b1 = std::min(hi, b0 + kBodyBlock);
      for (Index b = b0; b < b1; ++b)
        gather_body_force<false>(b, bc, a_side, s.gravity, bodies, s.refresh_live);
      for (Index b = b0; b < b1; ++b)
        update_body<kDamped, kLedger, false>(s, reference, bodies, balls, b, mine);
      for (Index b = b0; b < b1; ++b) place_balls(reference, bodies, balls, b, mine);
    }
  }
  out = mine;
}

// A sphere scene with a SIMD kernel: each sphere's gather, then the leapfrog of the
// share's spheres several at a time (sphere_kernel.hpp), the last few one by one.
template <bool kDamped, bool kLedger>
void step_spheres_in_lanes(const IntegratorSettings& s, ContactList& bc,
                           const std::vector<Wrench>& a_side, const std::vector<Vec3>& reference,
                           BodyStore& bodies, BallStore& balls, Index lo, Index hi,
                           ThreadReport& out) {
  for (Index b = lo; b < hi; ++b)
    gather_body_force<true>(b, bc, a_side, s.gravity, bodies, s.refresh_live);
  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Index) == sizeof(std::int32_t));
  SphereUpdateView u;
  u.force = flat(bodies.force);
  u.torque = flat(bodies.torque);
  u.velocity = flat(bodies.velocity);
  u.angular_velocity = flat(bodies.angular_velocity);
  u.position = flat(bodies.position);
  u.ball_position = flat(balls.position);
  u.rotation = flat(bodies.rotation);
  u.reference = flat(reference);
  u.mass = bodies.mass.data();
  u.inv_mass = bodies.inv_mass.data();
  u.inv_inertia = flat(bodies.inv_inertia);
  u.gravity_work = bodies.gravity_work.data();
  u.damping_dissipated = bodies.damping_dissipated.data();
  u.dt = s.dt;
  u.local_damping = s.local_damping;
  for (int k = 0; k < 3; ++k) u.gravity[k] = s.gravity[k];
  u.max_speed = s.max_speed;
  u.ledger = kLedger;
  SphereUpdateReport r;
  r.shift2 = out.shift2;
  r.bad = out.bad;
  const Index done = sphere_kernel_update(u, lo, hi, s.sphere_kernel_lanes, r);
  ThreadReport mine{r.shift2, r.bad};
  for (Index b = done; b < hi; ++b)
    update_body<kDamped, kLedger, true>(s, reference, bodies, balls, b, mine);
  out = mine;
}

}  // namespace

void integrate(const IntegratorSettings& s, ContactList& ball_contacts,
               const std::vector<Wrench>& a_side, const std::vector<Vec3>& reference,
               BodyStore& bodies, BallStore& balls, IntegrationReport& report) {
  ThreadReport mine;
  // Shares of bodies by work (work_split.hpp): a body costs its integration, its
  // balls and the side-b contacts it gathers.
  const auto [lo, hi] = balanced_range(
      bodies.size(),
      [&](Index b) {
        const Index first = b < bodies.size() ? bodies.first_ball[b] : balls.size();
        return long(first) + ball_contacts.b_first[first] + 4L * b;
      },
      s.split);
  // One instantiation per combination of local damping, ledger and sphere scene, so
  // that a scene pays for none of them it does not use, not even a test per body.
  with_flags(s.local_damping > 0.0, s.ledger, [&](auto damped, auto ledger) {
    constexpr bool kDamped = decltype(damped)::value, kLedger = decltype(ledger)::value;
    if (s.all_spheres && s.sphere_kernel_lanes > 0)
      step_spheres_in_lanes<kDamped, kLedger>(s, ball_contacts, a_side, reference, bodies, balls,
                                              lo, hi, mine);
    else if (s.all_spheres)
      step_bodies<kDamped, kLedger, true>(s, ball_contacts, a_side, reference, bodies, balls, lo,
                                          hi, mine);
    else
      step_bodies<kDamped, kLedger, false>(s, ball_contacts, a_side, reference, bodies, balls, lo,
                                           hi, mine);
  });

#pragma omp critical(ballast_integrate_report)
  {
    // Per-thread results combined with max/min: exact in any order, so the report
    // does not depend on the thread count. No barrier after it: the end of the
    // caller's parallel region is one (a barrier and an `omp single` here cost two
    // more waits per step).
    report.max_ball_shift2 = std::max(report.max_ball_shift2, mine.shift2);
    if (mine.bad != std::numeric_limits<Index>::max() &&
        (report.bad_body == kNoIndex || mine.bad < report.bad_body))
      report.bad_body = mine.bad;
  }
}

void finish_report(const BodyStore& bodies, IntegrationReport& report) {
  if (report.bad_body == kNoIndex) return;
  const Index b = report.bad_body;
  report.bad_is_nan = !std::isfinite(bodies.velocity[b].squaredNorm()) ||
                      !std::isfinite(bodies.angular_velocity[b].squaredNorm());
}

}  // namespace ballast
