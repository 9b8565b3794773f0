// Simulation's step: the bounds that decide which candidates the force pass visits,
// the walls' motion, and the one parallel region per step (force pass, barrier,
// gather and integration) with its phase timers. Set-up, the neighbour build and the
// queries are in simulation.cpp; docs/ARCHITECTURE.md, "One time step", walks through it.
#include "engine/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>

#include "engine/contact_laws.hpp"
#include "engine/errors.hpp"
#include "engine/forces.hpp"
#include "engine/integrator.hpp"
#include "engine/sphere_kernel.hpp"
#include "engine/sphere_planes.hpp"

namespace ballast {

// Each ball has moved at most D = shift_since_build_ since the build and each radius
// has grown at most G, so a gap can have closed by at most 2(D + G). The margin of
// 1e-9 skins covers the rounding of the distances (~1e-16 of a ball diameter), so a
// candidate beyond the bound is one the full test would also find apart.
double Simulation::growth_since_build() const {
  return std::max(0.0, size_scale_ - scale_at_build_) * max_full_radius_;
}

float Simulation::far_gap() const {
  constexpr float kNever = std::numeric_limits<float>::infinity();
  if (!settings_.skip_far_candidates) return kNever;
  const double bound = 2.0 * (shift_since_build_ + growth_since_build()) + 1e-9 * skin_;
  float f = static_cast<float>(bound);
  if (static_cast<double>(f) < bound) f = std::nextafter(f, kNever);  // round up
  return f;
}

// Twice the bound plus 2⁻¹⁶ skin: a bed whose bound grows from nothing to the skin
// between two builds (the half-skin rule) remakes its lists at most 16 times per
// build, and a settled one seldom. The headroom is small because a settled bed has
// many nearly touching pairs, each of which within it costs a distance test every
// step (the sphere bench bed: 1,232 of its 3,588 open candidates lie within 1/64
// skin, 516 within 1 µm; tests/bench/peers/near_gaps.py). Float arithmetic rounds to nearest, which
// cannot fall below `bound`, since 2·bound + m exceeds it.
float Simulation::live_cover_above(float bound) const {
  if (std::isinf(bound)) return bound;
  return 2.0f * bound + static_cast<float>(skin_ / 65536.0);
}

void Simulation::sum_wall_forces(std::vector<Vec3>& force) const {
  force.assign(walls_.size(), Vec3::Zero());
  // Every candidate is added: an open contact's stored wrench is zero (forces.cpp
  // open_contact), and adding it to a sum that starts at +0 changes no bits. The
  // test on `active` mispredicted about 200 times a step on the sphere bench bed, in
  // this serial part of the step that the other threads wait through.
  const Wrench* const wrench = wall_contacts_.b_wrench.data();
  const Index* const wall = wall_contacts_.b.data();
  for (Index c = 0; c < wall_contacts_.size(); ++c) force[wall[c]] += wrench[c].force;
}

template <class Law>
void Simulation::servo_contact_sums(const Servo& s, double& stiffness, double& dashpots) const {
  const double beta = settings_.damping_ratio;
  for (Index c = 0; c < wall_contacts_.size(); ++c) {
    if (!wall_contacts_.active[c]) continue;
    for (Index w : s.walls)
      if (wall_contacts_.b[c] == w) {
        // The contact's normal tangent stiffness at the force of the last pass.
        const Index ball = wall_contacts_.a[c];
        const PairProperties& p = pairs_.wall(balls_.material[ball], w);
        const double r = balls_.radius[ball];
        const double kn =
            Law::stiffness(p, r, Law::overlap_at(p, r, wall_contacts_.normal_force[c])).kn;
        stiffness += kn;
        if (beta > 0.0) dashpots += dashpot_coefficient(beta, bodies_.mass[balls_.body[ball]], kn);
      }
  }
}

void Simulation::drive_walls() {
  for (Servo& s : servos_) {
    // The measured force answers a wall speed u with K·u·dt through the contacts'
    // springs and with C·u through their normal dashpots, both by the next step; the
    // law divides by both. Divided by K·dt alone, a contact whose dashpot outweighs
    // its spring's step (C > K·dt/gain) made the wall overshoot every step: the
    // levelling plate on a bed settling with dashpots (β = 0.3) chattered at its
    // speed cap (tests/test_servo_law.cpp, DashpotOnTheContact...).
    double measured = 0.0, stiffness = 0.0, dashpots = 0.0;
    for (Index w : s.walls) measured -= wall_force_[w].dot(s.axis);
    with_contact_law(law_,
                     [&](auto law) { servo_contact_sums<decltype(law)>(s, stiffness, dashpots); });
    s.measured_force = measured;
    s.target_now = s.target_force(time_);
    const double error = s.target_now - measured;
    double speed = stiffness > 0.0 ? s.gain * error / (stiffness * dt_ + dashpots)
                                   : (error > 0.0 ? s.max_speed : -s.max_speed);
    speed = std::clamp(speed, -s.max_speed, s.max_speed);
    s.speed = speed;
    for (Index w : s.walls) walls_[w].velocity = speed * s.axis;
  }
  for (Index w = 0; w < static_cast<Index>(walls_.size()); ++w) {
    // The balls feel −wall_force. The work of the wall's last move is booked now that
    // the force after it is known, with the mean of the forces before and after: the
    // force before alone (a left Riemann sum) misses ½·K·Δx² on every move, always
    // the same sign, so a servo lid that moves every step made energy from nothing
    // (tests/test_energy_budget.cpp, a bed under a servo lid: 4 J in 0.12 s).
    wall_work_ -= 0.5 * (wall_force_at_move_[w] + wall_force_[w]).dot(wall_last_move_[w]);
    wall_last_move_[w] = dt_ * walls_[w].velocity;
    wall_force_at_move_[w] = wall_force_[w];
    advance_wall(walls_[w], dt_);
  }
}

Vec3 Simulation::wall_force(Index w) const {
  require_setup(w >= 0 && w < Index(walls_.size()), "wall index", w,
                "0 .. " + std::to_string(Index(walls_.size()) - 1));
  if (wall_forces_summed_) return wall_force_[w];
  std::vector<Vec3> force;  // the same sums the step makes while a wall moves
  sum_wall_forces(force);
  return force[w];
}

double Simulation::move_walls() {
  // Only a moving wall needs its force every step. In a fixed box (a settling bed,
  // the peer benchmark) the sums were a loop over every wall candidate on the main
  // thread, inside its share of the integration, reading on two threads half the
  // wrenches from the other core (docs/PERFORMANCE.md, "Wall forces when asked for"). Without
  // them drive_walls books no work (every velocity is zero) and moves nothing.
  // A wall that has just stopped still needs the force after its last move.
  wall_forces_summed_ = std::any_of(walls_.begin(), walls_.end(),
                                    [](const Wall& w) { return w.motion != WallMotion::Fixed; }) ||
                        std::any_of(wall_last_move_.begin(), wall_last_move_.end(),
                                    [](const Vec3& m) { return m != Vec3::Zero(); });
  if (wall_forces_summed_) sum_wall_forces(wall_force_);
  drive_walls();
  double shift2 = 0.0;
  for (Index w = 0; w < static_cast<Index>(walls_.size()); ++w)
    shift2 = std::max(shift2, (walls_[w].displacement - wall_reference_[w]).squaredNorm());
  return shift2;
}

void Simulation::step() {
  const double step_start = phase_timing_ ? omp_get_wtime() : 0.0;
  do_step();
  if (phase_timing_) {
    // The step outside the region: its whole time less what the threads' parts add up
    // to on the main thread.
    const PhaseTimes::Thread& main = phase_times_.thread[0];
    const double region = main.fork + main.contacts + main.barrier + main.integrate + main.join;
    const double step_seconds = omp_get_wtime() - step_start;
    phase_times_.serial += step_seconds - (region - phase_region_before_);
    phase_times_.step_seconds.push_back(float(step_seconds));
    phase_region_before_ = region;
  }
}

void Simulation::set_phase_timing(bool on) {
  phase_timing_ = on;
  phase_times_ = PhaseTimes{};
  phase_region_before_ = 0.0;
}

void Simulation::force_thread_shares(const TimedSplit::ShareRule& rule) {
  contact_split_.force_shares(rule);
  integrate_split_.force_shares(rule);
}

void Simulation::do_step() {
  if (!prepared_) prepare();
  if (needs_rebuild_) rebuild_neighbours();
  if (pairs_stale_) {
    pairs_.build(materials_, walls_, law_);
    pairs_stale_ = false;
  }
  const bool has_walls = !walls_.empty();
  // The live lists hold every candidate that can touch while the bound stays at or
  // below their cover; past it, raise the cover and remake them (contact_list.hpp).
  const float bound = far_gap();
  const bool refresh_live = !(bound <= ball_contacts_.live_cover);
  if (refresh_live) ball_contacts_.live_cover = live_cover_above(bound);
  // The SIMD sphere kernel takes the live candidates from one flat list, made here,
  // serially, whenever the live lists are remade (rare in a settled bed) or the
  // kernel comes into use; the side-b lists are then remade by the integrator.
  const int lanes = settings_.simd_lanes < 0 ? sphere_kernel_best_lanes() : settings_.simd_lanes;
  // The kernel is the linear law's (LinearLaw::kSphereKernel); another law's sphere
  // scene takes the scalar pass.
  const bool law_kernel = with_contact_law(law_, [](auto l) { return decltype(l)::kSphereKernel; });
  const bool kernel = all_spheres_ && law_kernel && settings_.damping_ratio == 0.0 && lanes > 0;
  kernel_lanes_ = kernel ? lanes : 0;
  const bool make_flat = kernel && (refresh_live || !ball_contacts_.flat_live_current);
  if (make_flat) {
    ball_contacts_.refresh_live_a(0, balls_.size());
    ball_contacts_.make_flat_live();
  } else if (refresh_live) {
    ball_contacts_.flat_live_current = false;  // the force pass remakes the lists below
  }
  // On one thread there is nothing to share, and the passes skip their timers.
  const int threads = omp_get_max_threads();
  contact_split_.prepare(threads);
  integrate_split_.prepare(threads);
  TimedSplit* const contact_split = threads > 1 ? &contact_split_ : nullptr;
  TimedSplit* const integrate_split = threads > 1 ? &integrate_split_ : nullptr;
  if (kernel && has_walls) fill_plane_table(walls_, plane_table_);
  const ForceSettings fs{.dt = dt_,
                         .law = law_,
                         .damping_ratio = settings_.damping_ratio,
                         .friction = friction_,
                         .all_spheres = all_spheres_,
                         .ledger = settings_.energy_ledger,
                         .sphere_kernel_lanes = kernel ? lanes : 0,
                         .planes = kernel && has_walls ? &plane_table_ : nullptr,
                         .refresh_live = refresh_live && !kernel,
                         .split = contact_split};
  const IntegratorSettings is{.dt = dt_,
                              .local_damping = settings_.local_damping,
                              .gravity = settings_.gravity,
                              .max_speed = settings_.max_speed,
                              .rotation = settings_.rotation,
                              .all_spheres = all_spheres_,
                              .ledger = settings_.energy_ledger,
                              .sphere_kernel_lanes = all_spheres_ ? lanes : 0,
                              .refresh_live = refresh_live || make_flat,
                              .split = integrate_split};
  IntegrationReport r;
  // One parallel region per step and one barrier inside it: the force pass
  // (forces.hpp), then per body gather + integrate (integrator.hpp); the region's end
  // is the second. After the barrier the main thread first sums the wall forces and
  // moves the walls (nothing the integration reads), inside its timed share, so the
  // split hands it fewer bodies instead of leaving the others waiting for it after
  // the region (1.6 µs a step on the sphere bench bed, about 2 % on two threads).
  double wall_shift2 = 0.0;
  std::exception_ptr wall_error;
  // Clock readings for the passes' shares (two threads or more) and for phase timing.
  const bool timing = phase_timing_;
  if (timing && phase_times_.thread.size() < std::size_t(threads))
    phase_times_.thread.resize(threads);
  if (timing) phase_end_.assign(threads, 0.0);
  const double region_start = timing ? omp_get_wtime() : 0.0;
  // The region runs on one thread too: a step of a study run is itself inside the
  // study's team of jobs, and without a region of its own the passes would split
  // their loops by that outer team.
#pragma omp parallel
  {
    const int me = omp_get_thread_num();
    const bool clock = timing || contact_split != nullptr;
    const double t0 = clock ? omp_get_wtime() : 0.0;
    compute_contacts(balls_, bodies_, pairs_, walls_, fs, ball_contacts_, wall_contacts_, a_side_);
    const double t1 = clock ? omp_get_wtime() : 0.0;
    if (contact_split != nullptr) contact_split->record(me, t1 - t0);
#pragma omp barrier
    const double t2 = clock ? omp_get_wtime() : 0.0;
    if (me == 0 && has_walls) {
      try {  // an exception must not leave the region
        wall_shift2 = move_walls();
      } catch (...) {
        wall_error = std::current_exception();
      }
    }
    integrate(is, ball_contacts_, a_side_, reference_positions_, bodies_, balls_, r);
    const double t3 = clock ? omp_get_wtime() : 0.0;
    if (integrate_split != nullptr) integrate_split->record(me, t3 - t2);
    if (timing) {  // each thread its own entry
      PhaseTimes::Thread& p = phase_times_.thread[me];
      p.fork += t0 - region_start;
      p.contacts += t1 - t0;
      p.barrier += t2 - t1;
      p.integrate += t3 - t2;
      phase_end_[me] = t3;
      // The join is known after the region; the main thread fills it in there.
      p.per_step.push_back(
          {float(t0 - region_start), float(t1 - t0), float(t2 - t1), float(t3 - t2), 0.0f});
    }
  }
  if (timing) close_phase_times(threads);
  contact_split_.update();
  integrate_split_.update();
  if (wall_error) std::rethrow_exception(wall_error);
  finish_report(bodies_, r);
  if (r.bad_body != kNoIndex) throw_blow_up(r);
  shift_since_build_ = std::sqrt(r.max_ball_shift2);
  time_ += dt_;
  ++steps_;
  schedule_rebuild(wall_shift2, refresh_live || make_flat);
}

void Simulation::close_phase_times(int threads) {
  const double region_end = omp_get_wtime();
  for (int t = 0; t < threads; ++t) {
    PhaseTimes::Thread& p = phase_times_.thread[t];
    p.join += region_end - phase_end_[t];
    if (!p.per_step.empty()) p.per_step.back()[4] = float(region_end - phase_end_[t]);
  }
  ++phase_times_.steps;
}

void Simulation::throw_blow_up(const IntegrationReport& r) const {
  std::ostringstream m;
  m << "step " << steps_ << ": body " << r.bad_body;
  if (r.bad_is_nan) {
    m << " velocity is not finite (NaN or Inf)";
  } else {
    m << " speed " << bodies_.velocity[r.bad_body].norm() << " m/s exceeds max_speed "
      << settings_.max_speed << " m/s: kinetic energy is exploding";
  }
  m << " (dt = " << dt_ << " s, critical estimate " << estimate_.critical << " s)";
  throw SimulationError(steps_, r.bad_body, r.bad_is_nan ? "velocity" : "speed", m.str());
}

void Simulation::schedule_rebuild(double wall_shift2, bool lists_remade) {
  // Contacts form between rebuilds too (a bed being squeezed): refresh the
  // automatic timestep often enough that it never trails them by much.
  if (!settings_.fixed_dt && steps_ % kTimestepRefreshSteps == 0) update_timestep();
  const double half = 0.5 * skin_;
  const bool required =
      shift_since_build_ + growth_since_build() > half || wall_shift2 > half * half;
  // The live lists were remade this step (by the force pass, the gather or the kernel's
  // flat sequence): count them for the rebuild policy, serially, a few times a build.
  if (lists_remade) rebuild_policy_.live_count(live_candidates());
  const bool pays = rebuild_policy_.step_taken() && settings_.adaptive_rebuild;
  if (!needs_rebuild_ && !required && pays) ++early_builds_;
  needs_rebuild_ = needs_rebuild_ || required || pays;
}

long Simulation::live_candidates() const {
  const ContactList& c = ball_contacts_;
  long n = 0;
  for (std::size_t i = 0; i < c.live_a_end.size(); ++i) n += c.live_a_end[i] - c.a_first[i];
  return n;
}

}  // namespace ballast
