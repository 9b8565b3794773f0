// The facade a scene talks to. It owns the stores and runs the one time-step loop:
//
//   step():  ball–ball contacts → ball–wall contacts → gather into bodies (+gravity)
//            → integrate (damping, leapfrog, re-place balls) → walls and servos move
//            → rebuild neighbours if anything moved more than half the skin.
//
// A scene pays only for what it uses: no walls, no wall loop; no friction anywhere,
// no shear history; spheres take the isotropic rotation path.
#pragma once

#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/ball_store.hpp"
#include "engine/body_store.hpp"
#include "engine/cell_list.hpp"
#include "engine/clump_template.hpp"
#include "engine/contact_list.hpp"
#include "engine/diagnostics.hpp"
#include "engine/material.hpp"
#include "engine/pair_table.hpp"
#include "engine/phase_times.hpp"
#include "engine/rebuild_policy.hpp"
#include "engine/rigid_rotation.hpp"
#include "engine/servo.hpp"
#include "engine/spatial_order.hpp"
#include "engine/sphere_planes.hpp"
#include "engine/timed_split.hpp"
#include "engine/timestep.hpp"
#include "engine/walls.hpp"

namespace ballast {

struct IntegrationReport;  // integrator.hpp
class StateWriter;         // state_io.hpp
class StateReader;

struct SimulationSettings {
  Vec3 domain_lo = Vec3::Zero();  // m: every ball centre must stay in [lo, hi]
  Vec3 domain_hi = Vec3::Ones();
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);  // m/s²
  double local_damping = 0.7;            // PFC α; 0 switches it off
  double damping_ratio = 0.0;            // viscous contact damping ratio β; 0: none
  std::optional<double> fixed_dt;        // s; unset: automatic = dt_safety × critical
  double dt_safety = 0.8;
  bool strict_timestep = false;        // a fixed dt above critical is an error, not a warning
  std::optional<double> skin;          // m; unset: 0.2 × mean ball radius
  double max_speed = 100.0;            // m/s; a body faster than this means blow-up
  std::string contact_law = "linear";  // a name from ContactLaws (contact_laws.hpp)
  RotationIntegrator rotation = RotationIntegrator::kPfc;  // clumps: "pfc" or "full"
  // A scene of spheres only takes the force pass's and the integrator's sphere path
  // (same sums in the same order, so the same bits); false forces the general path,
  // for the test and the benchmark that compare the two.
  bool sphere_fast_path = true;
  // Candidates that cannot touch since the last build are not evaluated (contact_list.hpp,
  // "Far candidates"): the same bits, less work; false evaluates every candidate,
  // for the test that checks the skip changes nothing.
  bool skip_far_candidates = true;
  // Rebuild the neighbour list early when that lowers the mean cost per step
  // (rebuild_policy.hpp): with a fixed dt the same bits, fewer live candidates; false
  // keeps only the half-skin rule, for the test and the benchmark that compare them.
  bool adaptive_rebuild = true;
  // Lanes of the SIMD kernel that evaluates a sphere scene's ball–ball contacts when
  // it has no dashpots (sphere_kernel.hpp): -1 the widest this CPU runs, 0 none (the
  // scalar pass), 4 AVX2, 8 AVX-512. Every choice gives the same bits.
  int simd_lanes = -1;
  // Book every joule each step (the work of gravity, local damping, Coulomb slip and
  // dashpots), so that energy() closes its balance: a blow-up check and a report the
  // box test keeps. false: a scene that reports no energy budget (the peer benchmark's
  // bed) does none of that work; energy() then gives kinetic and elastic energy only.
  // It costs 1–4 % of a step's instructions (docs/PERFORMANCE.md, "What a scene pays
  // for"). A moving wall's work is summed either way: a few operations per wall, from
  // the force its servo measures anyway.
  bool energy_ledger = true;
  std::ostream* log = nullptr;  // where the start-up report goes (nullptr: silent)
};

class Simulation {
 public:
  // Steps between re-estimates of the automatic timestep (besides every rebuild).
  static constexpr long kTimestepRefreshSteps = 100;

  explicit Simulation(const SimulationSettings& settings);

  // ---- building the scene (before the first step) ----
  Index add_material(const Material& m);
  Index add_sphere(const Vec3& x, double radius, double density, Index material);
  // A rigid clump: ball offsets in its principal frame about the centre of mass,
  // mass and principal moments already computed (see clump_mass).
  Index add_clump(const Vec3& x, const Quat& orientation, std::span<const Vec3> offsets,
                  std::span<const double> radii, double mass, const Vec3& principal_inertia,
                  Index material);
  // A clump from the generator (engine/clump_generator.hpp, clump_mass.hpp).
  Index add_clump(const Vec3& x, const Quat& orientation, const ClumpTemplate& t, Index material) {
    return add_clump(x, orientation, t.offsets, t.radii, t.mass, t.principal_inertia, material);
  }
  Index add_wall(const Wall& w);
  // Renumbers the bodies and their balls cell by cell (engine/spatial_order.hpp)
  // when that pays, or always with `always`: for beds that come in another code's
  // order. Before the first step only (no contact history yet). Returns the order
  // (order[k]: the body's index before, of the new body k) and whether it was applied;
  // a caller that keeps anything per body renumbers it by the order.
  SpatialOrder sort_bodies_spatially(bool always = false);
  Index add_servo(const Servo& s);
  // Stops a servo: its walls stand still from now on (motion Fixed, velocity zero)
  // and the servos after it move down one index.
  void release_servo(Index servo);

  // ---- changing conditions during a run ----
  void set_gravity(const Vec3& g) { settings_.gravity = g; }
  // Clumps' rotation integrator; switching to `full` derives each body's angular
  // momentum from its current ω.
  void set_rotation_integrator(RotationIntegrator r);
  void set_local_damping(double alpha);
  // SimulationSettings::sphere_fast_path; takes effect at the next step.
  void set_sphere_fast_path(bool on);
  void set_damping_ratio(double beta);  // viscous contact damping; dt follows at next build
  void set_material_friction(Index material, double mu);
  void set_wall_friction(Index wall, double mu);
  void set_all_friction(double mu);  // every material and wall: the paper's 0.3 → 0.5 switch
  void set_wall_velocity(Index wall, const Vec3& v);
  // Moves a wall at once by `delta`, m (lifting the lid off a prepared sample). No
  // work is booked: move a wall only when the contacts it opens carry no load.
  void move_wall(Index wall, const Vec3& delta);
  // Replaces a servo's target force history, N as a function of time, s.
  void set_servo_target(Index servo, std::function<double(double)> target);
  void set_body_velocity(Index body, const Vec3& v);
  void set_body_angular_velocity(Index body, const Vec3& w);
  // Every body at rest at once (PFC users' velocity reset after radius expansion);
  // the kinetic energy removed is booked as damping.
  void quench();
  // Displacements and accumulated rotations are measured from now on (the box test
  // resets at the start of loading and of unloading).
  void reset_motion_reference();
  // PFC-style radius expansion: every ball's radius and every clump's ball offsets
  // become `scale` × their values as added, about each body's centre of mass;
  // masses and inertias keep their full-size values. A scene adds particles at full
  // size, shrinks them before the first step and grows them back while cycling
  // (the paper's sample preparation). scale in (0, 1].
  void set_size_scale(double scale);
  double size_scale() const { return size_scale_; }

  // ---- running ----
  // Validates the scene, builds neighbours, sets dt and prints the dt report.
  // Called by the first step() if not called before.
  void prepare();
  void step();
  void run(long steps);

  // ---- reading ----
  double time() const { return time_; }
  long step_count() const { return steps_; }
  double dt() const { return dt_; }
  double critical_dt() const { return estimate_.critical; }
  double skin() const { return skin_; }
  // Lanes of the SIMD sphere kernel the last step used (sphere_kernel.hpp); 0: the
  // scalar pass.
  int sphere_kernel_lanes() const { return kernel_lanes_; }
  // Per-thread phase timing of the steps from now on (phase_times.hpp); off by default.
  void set_phase_timing(bool on);
  const PhaseTimes& phase_times() const { return phase_times_; }
  // Test hook: the force pass's and the integrator's thread shares from `rule`
  // (timed_split.hpp) instead of measured time, for determinism tests that must not
  // depend on the clock; an empty rule: measured time again.
  void force_thread_shares(const TimedSplit::ShareRule& rule);
  long neighbour_builds() const { return builds_; }
  // Of those, the builds the rebuild policy asked for before the half-skin rule did.
  long early_neighbour_builds() const { return early_builds_; }
  // Ball–ball candidates on the live lists now: those the force pass evaluates.
  long live_candidates() const;
  const SimulationSettings& settings() const { return settings_; }
  const BodyStore& bodies() const { return bodies_; }
  const BallStore& balls() const { return balls_; }
  const std::vector<Wall>& walls() const { return walls_; }
  const std::vector<Servo>& servos() const { return servos_; }
  const std::vector<Material>& materials() const { return materials_; }
  const ContactList& ball_contacts() const { return ball_contacts_; }
  const ContactList& wall_contacts() const { return wall_contacts_; }
  // Force the balls exert on wall w at the last step, N. Summed every step while a
  // wall moves (its work, a servo's measurement); otherwise here, when asked for,
  // in the same order, so the same bits.
  Vec3 wall_force(Index w) const;

  EnergyBudget energy() const;
  ContactStats contacts() const;
  double unbalanced_force_ratio() const;

  // ---- checkpoints (engine/state_io.hpp; simulation_state.cpp) ----
  // Writes every field the next steps read, settings included: a simulation that
  // loads it steps on bit for bit as this one would, on the same number of threads.
  // Left out: the servos' target functions (code, not data: the caller sets them again
  // with set_servo_target before the next step), the log stream, and the thread
  // shares and phase timers, which move no bit.
  void save_state(StateWriter& out) const;
  // Replaces this simulation's whole state by one save_state wrote; keeps the log.
  void load_state(StateReader& in);

 private:
  template <class Io>
  void state_fields(Io& io);
  void validate() const;
  void rebuild_neighbours();
  void update_timestep();
  // all_spheres_ from the bodies and settings_.sphere_fast_path (prepare() and the setter).
  void refresh_all_spheres();
  void do_step();  // step() without the phase clock around it
  // m: the most any radius has grown since the last build (radius expansion).
  double growth_since_build() const;
  float far_gap() const;
  // A live_cover for the ball–ball list above `bound` (m), with headroom so that a
  // moving bed remakes its live lists a few times per build rather than every step.
  float live_cover_above(float bound) const;
  // Each wall's force from the balls, N: the wall candidates' wrenches in list order.
  void sum_wall_forces(std::vector<Vec3>& force) const;
  void drive_walls();
  // The end of do_step: each thread's join time; the error of a body that blew up
  // (step, body, quantity); the automatic dt's refresh and whether the neighbour
  // list is rebuilt before the next step (the half-skin rule, a wall's move, or the
  // rebuild policy; lists_remade: the live lists were remade this step).
  void close_phase_times(int threads);
  [[noreturn]] void throw_blow_up(const IntegrationReport& r) const;
  void schedule_rebuild(double wall_shift2, bool lists_remade);
  // Both, then the largest squared wall move since the last build (m²).
  double move_walls();
  // Adds servo s's wall contacts' normal tangent stiffnesses (N/m, at the normal
  // force of the last force pass) and their normal dashpots (N·s/m): what the servo
  // law divides by. One instantiation per contact law.
  template <class Law>
  void servo_contact_sums(const Servo& s, double& stiffness, double& dashpots) const;
  bool scene_has_friction() const;
  void refresh_friction_state();

  SimulationSettings settings_;
  std::vector<Material> materials_;
  BallStore balls_;
  BodyStore bodies_;
  std::vector<Wall> walls_;
  std::vector<Servo> servos_;
  int law_ = 0;      // settings_.contact_law's number in ContactLaws; -1: unknown (refused)
  PairTable pairs_;  // combined contact properties; rebuilt when pairs_stale_
  CellList cells_;
  ContactList ball_contacts_, wall_contacts_;
  std::vector<Wrench> a_side_;  // per body, this step: wrenches of its balls' side-a contacts
  // Thread shares of the force pass and of the integrator, following measured time
  // (timed_split.hpp): they move which thread computes a body, never a bit.
  TimedSplit contact_split_, integrate_split_;
  PlaneTable plane_table_;  // the walls as the sphere kernel reads them, made each step
  std::vector<Vec3> reference_positions_;  // ball positions at the last neighbour build
  std::vector<Vec3> wall_reference_;       // wall displacements at the last build
  std::vector<Vec3> wall_force_;           // current only while wall_forces_summed_
  // Each wall's last move (m) and the force on it when it made it (N): its work is
  // booked at the next step, by the trapezoid rule over the two forces (drive_walls).
  std::vector<Vec3> wall_last_move_, wall_force_at_move_;
  bool wall_forces_summed_ = false;
  double wall_work_ = 0.0;
  // Radius expansion (set_size_scale): full-size geometry, kept only once used.
  std::vector<double> full_radius_;
  std::vector<Vec3> full_offset_;
  double size_scale_ = 1.0, scale_at_build_ = 1.0, max_full_radius_ = 0.0;
  TimestepEstimate estimate_;  // the last critical-timestep estimate
  double time_ = 0.0, dt_ = 0.0, skin_ = 0.0, max_radius_ = 0.0;
  // m: the largest distance any ball has moved from reference_positions_ (the last
  // build), as of the last update of the positions; it bounds how far a gap can close.
  double shift_since_build_ = 0.0;
  long steps_ = 0, builds_ = 0, early_builds_ = 0;
  RebuildPolicy rebuild_policy_;  // early builds (adaptive_rebuild)
  bool prepared_ = false, friction_ = false, needs_rebuild_ = false, pairs_stale_ = true;
  bool all_spheres_ = false;  // ForceSettings::all_spheres, from refresh_all_spheres()
  int kernel_lanes_ = 0;      // ForceSettings::sphere_kernel_lanes of the last step
  bool phase_timing_ = false;
  PhaseTimes phase_times_;
  std::vector<double> phase_end_;     // s, each thread's end of the region, this step
  double phase_region_before_ = 0.0;  // s, the main thread's region parts before this step
};

}  // namespace ballast
