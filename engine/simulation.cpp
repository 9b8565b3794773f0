// Simulation's set-up (bodies, walls, materials, settings and their validation), the
// neighbour build and the queries. The step itself is in simulation_step.cpp.
#include "engine/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <sstream>

#include "engine/contact_laws.hpp"
#include "engine/errors.hpp"
#include "engine/forces.hpp"
#include "engine/integrator.hpp"
#include "engine/sphere_kernel.hpp"
#include "engine/timestep.hpp"

namespace ballast {

namespace {

bool inside(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
}

std::string vec_str(const Vec3& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

void validate_material(const Material& m, Index id, int law) {
  const std::string f = "material " + std::to_string(id) + " ";
  check_law_parameters(law, m, f);
  require_setup(m.mu >= 0.0 && std::isfinite(m.mu), f + "mu", m.mu, ">= 0");
}

}  // namespace

Simulation::Simulation(const SimulationSettings& settings)
    : settings_(settings), law_(contact_law_index(settings.contact_law)) {
  require_setup((settings_.domain_hi - settings_.domain_lo).minCoeff() > 0.0,
                "domain extent (hi - lo, smallest)",
                (settings_.domain_hi - settings_.domain_lo).minCoeff(), "> 0 m");
}

Index Simulation::add_material(const Material& m) {
  validate_material(m, static_cast<Index>(materials_.size()), law_);
  materials_.push_back(m);
  refresh_friction_state();
  return static_cast<Index>(materials_.size()) - 1;
}

Index Simulation::add_sphere(const Vec3& x, double radius, double density, Index material) {
  require_setup(radius > 0.0 && std::isfinite(radius), "sphere radius", radius, "> 0 m");
  require_setup(density > 0.0 && std::isfinite(density), "sphere density", density, "> 0 kg/m^3");
  const double mass = density * 4.0 / 3.0 * kPi * radius * radius * radius;
  const double inertia = 0.4 * mass * radius * radius;
  const double r = radius;
  return add_clump(x, Quat::Identity(), std::span<const Vec3>{}, {&r, 1}, mass,
                   Vec3::Constant(inertia), material);
}

Index Simulation::add_clump(const Vec3& x, const Quat& orientation, std::span<const Vec3> offsets,
                            std::span<const double> radii, double mass,
                            const Vec3& principal_inertia, Index material) {
  // An empty offsets span means "one ball at the centre" (add_sphere).
  const bool sphere = offsets.empty() && radii.size() == 1;
  require_setup(sphere || offsets.size() == radii.size(), "clump offsets count", offsets.size(),
                "the number of radii (" + std::to_string(radii.size()) + ")");
  require_setup(!radii.empty(), "clump ball count", 0, ">= 1");
  require_setup(mass > 0.0 && std::isfinite(mass), "body mass", mass, "> 0 kg");
  require_setup(principal_inertia.minCoeff() > 0.0 && principal_inertia.allFinite(),
                "body principal inertia (smallest)", principal_inertia.minCoeff(), "> 0 kg m^2");
  require_setup(
      material >= 0 && material < static_cast<Index>(materials_.size()), "ball material index",
      material,
      "0.." + std::to_string(static_cast<long>(materials_.size()) - 1) + " (add_material first)");
  const Index body = bodies_.size();
  const Index first = balls_.size();
  const Mat3 rot = orientation.normalized().toRotationMatrix();
  for (std::size_t k = 0; k < radii.size(); ++k) {
    require_setup(radii[k] > 0.0 && std::isfinite(radii[k]), "ball radius", radii[k], "> 0 m");
    const Vec3 off = sphere ? Vec3::Zero() : offsets[k];
    const Vec3 p = x + rot * off;
    require_setup(inside(p, settings_.domain_lo, settings_.domain_hi), "ball position", vec_str(p),
                  "inside the domain " + vec_str(settings_.domain_lo) + " .. " +
                      vec_str(settings_.domain_hi));
    balls_.add(p, radii[k], body, material, off);
    max_radius_ = std::max(max_radius_, radii[k]);
  }
  bodies_.add(x, orientation, mass, principal_inertia, first, static_cast<Index>(radii.size()),
              sphere);
  prepared_ = false;
  return body;
}

Index Simulation::add_wall(const Wall& w) {
  validate_wall(w, law_);
  walls_.push_back(w);
  wall_force_.push_back(Vec3::Zero());
  wall_last_move_.push_back(Vec3::Zero());
  wall_force_at_move_.push_back(Vec3::Zero());
  refresh_friction_state();
  prepared_ = false;
  return static_cast<Index>(walls_.size()) - 1;
}

Index Simulation::add_servo(const Servo& s) {
  validate_servo(s, static_cast<Index>(walls_.size()));
  for (Index w : s.walls) walls_[w].motion = WallMotion::Servo;
  servos_.push_back(s);
  return static_cast<Index>(servos_.size()) - 1;
}

void Simulation::release_servo(Index servo) {
  require_setup(servo >= 0 && servo < static_cast<Index>(servos_.size()), "servo index", servo,
                "an existing servo");
  for (Index w : servos_[servo].walls) {
    walls_[w].motion = WallMotion::Fixed;
    walls_[w].velocity = Vec3::Zero();
  }
  servos_.erase(servos_.begin() + servo);
}

void Simulation::set_rotation_integrator(RotationIntegrator r) {
  if (r == RotationIntegrator::kFull && settings_.rotation != r)
    for (Index b = 0; b < bodies_.size(); ++b)
      bodies_.angular_momentum[b] = spin_angular_momentum(
          bodies_.orientation[b], bodies_.inertia[b], bodies_.angular_velocity[b]);
  settings_.rotation = r;
}

void Simulation::set_sphere_fast_path(bool on) {
  settings_.sphere_fast_path = on;
  refresh_all_spheres();
}

void Simulation::refresh_all_spheres() {
  // A scene of spheres only, added in order (ball k is body k), takes the force
  // pass's and the integrator's sphere path, which reads neither ball owners nor
  // sphere flags (forces.cpp, integrator.cpp).
  all_spheres_ = settings_.sphere_fast_path;
  for (Index b = 0; b < bodies_.size() && all_spheres_; ++b)
    all_spheres_ = bodies_.is_sphere[b] && bodies_.first_ball[b] == b;
}

void Simulation::set_local_damping(double alpha) {
  require_setup(alpha >= 0.0 && alpha < 1.0, "local damping alpha", alpha, "[0, 1)");
  settings_.local_damping = alpha;
}

void Simulation::set_damping_ratio(double beta) {
  require_setup(beta >= 0.0 && beta < 1.0, "damping_ratio", beta, "[0, 1)");
  settings_.damping_ratio = beta;
  if (prepared_ && !settings_.fixed_dt) update_timestep();
}

void Simulation::set_material_friction(Index material, double mu) {
  require_setup(material >= 0 && material < static_cast<Index>(materials_.size()), "material index",
                material, "an existing material");
  require_setup(mu >= 0.0 && std::isfinite(mu), "friction mu", mu, ">= 0");
  materials_[material].mu = mu;
  refresh_friction_state();
}

void Simulation::set_wall_friction(Index wall, double mu) {
  require_setup(wall >= 0 && wall < static_cast<Index>(walls_.size()), "wall index", wall,
                "an existing wall");
  require_setup(mu >= 0.0 && std::isfinite(mu), "friction mu", mu, ">= 0");
  walls_[wall].material.mu = mu;
  refresh_friction_state();
}

void Simulation::set_all_friction(double mu) {
  for (Index m = 0; m < static_cast<Index>(materials_.size()); ++m) set_material_friction(m, mu);
  for (Index w = 0; w < static_cast<Index>(walls_.size()); ++w) set_wall_friction(w, mu);
}

void Simulation::set_wall_velocity(Index wall, const Vec3& v) {
  require_setup(wall >= 0 && wall < static_cast<Index>(walls_.size()), "wall index", wall,
                "an existing wall");
  require_setup(walls_[wall].motion != WallMotion::Servo, "velocity of servo-driven wall",
                walls_[wall].name, "a wall not under servo control");
  walls_[wall].velocity = v;
  walls_[wall].motion = v.isZero(0.0) ? WallMotion::Fixed : WallMotion::Prescribed;
}

void Simulation::set_servo_target(Index servo, std::function<double(double)> target) {
  require_setup(servo >= 0 && servo < static_cast<Index>(servos_.size()), "servo index", servo,
                "an existing servo");
  require_setup(static_cast<bool>(target), "servo target force", "empty", "a function of time");
  servos_[servo].target_force = std::move(target);
}

void Simulation::move_wall(Index wall, const Vec3& delta) {
  require_setup(wall >= 0 && wall < static_cast<Index>(walls_.size()), "wall index", wall,
                "an existing wall");
  Wall& w = walls_[wall];
  w.point += delta;
  w.lo += delta;
  w.hi += delta;
  w.displacement += delta;
  needs_rebuild_ = true;
}

void Simulation::set_body_velocity(Index body, const Vec3& v) {
  bodies_.velocity.at(body) = v;
}

void Simulation::set_body_angular_velocity(Index body, const Vec3& w) {
  bodies_.angular_velocity.at(body) = w;
  bodies_.angular_momentum[body] =
      spin_angular_momentum(bodies_.orientation[body], bodies_.inertia[body], w);
}

void Simulation::quench() {
  for (Index b = 0; b < bodies_.size(); ++b) {
    // Book each body's kinetic energy as damping, so the energy budget still closes.
    if (settings_.energy_ledger) {
      const Vec3 w = bodies_.orientation[b].conjugate() * bodies_.angular_velocity[b];
      bodies_.damping_dissipated[b] += 0.5 * bodies_.mass[b] * bodies_.velocity[b].squaredNorm() +
                                       0.5 * w.dot(bodies_.inertia[b].cwiseProduct(w));
    }
    bodies_.velocity[b].setZero();
    bodies_.angular_velocity[b].setZero();
    bodies_.angular_momentum[b].setZero();
  }
}

void Simulation::reset_motion_reference() {
  bodies_.reset_motion_reference();
}

void Simulation::set_size_scale(double scale) {
  require_setup(scale > 0.0 && scale <= 1.0, "size scale", scale, "(0, 1]");
  if (full_radius_.empty()) {
    full_radius_ = balls_.radius;
    full_offset_ = balls_.offset;
    max_full_radius_ = max_radius_;
  }
  size_scale_ = scale;
  const Index n_bodies = bodies_.size();
  const bool measure = prepared_;
  // Raw pointers, taken once: through the containers, each store into a ball's
  // radius made GCC reload the data pointers of every vector the next ball reads.
  double* const radius = balls_.radius.data();
  Vec3* const offset = balls_.offset.data();
  Vec3* const position = balls_.position.data();
  const double* const full_radius = full_radius_.data();
  const Vec3* const full_offset = full_offset_.data();
  const Vec3* const reference = reference_positions_.data();
  double shift2 = 0.0;
  // Every step of a radius expansion comes here, for every ball (63,810 in a Sample 2
  // bed), so the loop runs on the step's threads, body by body: a body's position
  // and orientation are loaded once for all its balls. Each ball is its own work and
  // max is exact in any order: the result does not depend on the thread count.
#pragma omp parallel for schedule(static) reduction(max : shift2)
  for (Index b = 0; b < n_bodies; ++b) {
    const Index first = bodies_.first_ball[b], last = first + bodies_.ball_count[b];
    const bool clump = !bodies_.is_sphere[b];
    const Vec3 centre = bodies_.position[b];
    const Quat q = bodies_.orientation[b];
    for (Index k = first; k < last; ++k) {
      radius[k] = scale * full_radius[k];
      offset[k] = scale * full_offset[k];
      if (clump) position[k] = centre + q * offset[k];
      if (measure) shift2 = std::max(shift2, (position[k] - reference[k]).squaredNorm());
    }
  }
  max_radius_ = scale * max_full_radius_;
  // A pair listed at the last build stays valid while shift_a + shift_b plus the
  // growth of r_a + r_b stays below the skin.
  if (prepared_) shift_since_build_ = std::sqrt(shift2);
  if (prepared_ && shift_since_build_ + growth_since_build() > 0.5 * skin_) needs_rebuild_ = true;
}

bool Simulation::scene_has_friction() const {
  for (const Material& m : materials_)
    if (m.mu > 0.0) return true;
  for (const Wall& w : walls_)
    if (w.material.mu > 0.0) return true;
  return false;
}

void Simulation::refresh_friction_state() {
  pairs_stale_ = true;  // called whenever a material or wall property changes
  const bool now = scene_has_friction();
  if (now == friction_) return;
  friction_ = now;
  ball_contacts_.set_history(now);
  wall_contacts_.set_history(now);
}

void Simulation::validate() const {
  for (Index m = 0; m < static_cast<Index>(materials_.size()); ++m)
    validate_material(materials_[m], m, law_);
  for (const Wall& w : walls_) validate_wall(w, law_);
  for (const Servo& s : servos_) validate_servo(s, static_cast<Index>(walls_.size()));
  const auto& s = settings_;
  require_setup(s.local_damping >= 0.0 && s.local_damping < 1.0, "local_damping", s.local_damping,
                "[0, 1)");
  require_setup(s.damping_ratio >= 0.0 && s.damping_ratio < 1.0, "damping_ratio", s.damping_ratio,
                "[0, 1)");
  require_setup(s.dt_safety > 0.0 && s.dt_safety <= 1.0, "dt_safety", s.dt_safety, "(0, 1]");
  if (s.fixed_dt)
    require_setup(*s.fixed_dt > 0.0 && std::isfinite(*s.fixed_dt), "dt", *s.fixed_dt, "> 0 s");
  if (s.skin) require_setup(*s.skin > 0.0, "skin", *s.skin, "> 0 m");
  require_setup(s.max_speed > 0.0, "max_speed", s.max_speed, "> 0 m/s");
  require_setup(s.simd_lanes == -1 || s.simd_lanes == 0 || sphere_kernel_supported(s.simd_lanes),
                "simd_lanes", s.simd_lanes,
                std::string("-1 (the widest), 0 (none)") +
                    (sphere_kernel_supported(4) ? ", 4" : "") +
                    (sphere_kernel_supported(8) ? ", 8" : "") + " on this CPU");
  require_setup(s.gravity.allFinite(), "gravity", vec_str(s.gravity), "finite");
  require_setup(law_ >= 0, "contact_law", "'" + s.contact_law + "'", contact_law_names());
}

void Simulation::prepare() {
  validate();
  if (!settings_.skin) {
    double sum = 0.0;
    for (double r : balls_.radius) sum += r;
    skin_ = balls_.size() > 0 ? 0.2 * sum / balls_.size() : 1e-3;
  } else {
    skin_ = *settings_.skin;
  }
  rebuild_neighbours();
  update_timestep();
  refresh_all_spheres();
  prepared_ = true;
  needs_rebuild_ = false;
  const double ratio = dt_ / estimate_.critical;
  if (settings_.log) {
    *settings_.log << "timestep: dt = " << dt_ << " s, critical = " << estimate_.critical
                   << " s, dt/dt_critical = " << ratio
                   << (settings_.fixed_dt ? " (fixed)" : " (automatic)") << "; limited by body "
                   << estimate_.limiting_body
                   << (estimate_.limited_by_rotation ? " (mostly rotation)"
                                                     : " (mostly translation)")
                   << "\n";
  }
  if (settings_.fixed_dt && ratio > 1.0) {
    std::ostringstream m;
    m << "dt = " << dt_ << " s exceeds the critical timestep estimate " << estimate_.critical
      << " s (dt/dt_critical = " << ratio << ")";
    if (settings_.strict_timestep) throw SetupError(m.str() + " and strict_timestep is on");
    if (settings_.log) *settings_.log << "warning: " << m.str() << "; the run may blow up\n";
  }
}

void Simulation::update_timestep() {
  estimate_ = estimate_critical_timestep(balls_, bodies_, materials_, walls_, ball_contacts_,
                                         wall_contacts_, settings_.damping_ratio, law_,
                                         settings_.max_speed);
  dt_ = settings_.fixed_dt ? *settings_.fixed_dt : settings_.dt_safety * estimate_.critical;
}

void Simulation::rebuild_neighbours() {
  const Index n = balls_.size();
  for (Index k = 0; k < n; ++k) {
    if (inside(balls_.position[k], settings_.domain_lo, settings_.domain_hi)) continue;
    throw SimulationError(steps_, balls_.body[k], "position",
                          "step " + std::to_string(steps_) + ": body " +
                              std::to_string(balls_.body[k]) + " left the domain (ball at " +
                              vec_str(balls_.position[k]) + ")");
  }
  // The list is about to be replaced: hand what its contacts dissipated to the balls.
  ball_contacts_.flush_dissipation(balls_.friction_dissipated, balls_.viscous_dissipated);
  wall_contacts_.flush_dissipation(balls_.friction_dissipated, balls_.viscous_dissipated);
  cells_.build(balls_.position, settings_.domain_lo, settings_.domain_hi,
               2.0 * max_radius_ + skin_);
  std::vector<Index> a, b;
  find_candidate_pairs(cells_, balls_.position, balls_.radius, balls_.body, skin_, a, b);
  ball_contacts_.rebuild(std::move(a), std::move(b), friction_, n, true);

  std::vector<Index> wa, wb;
  if (!walls_.empty()) find_wall_candidates(walls_, balls_.position, balls_.radius, skin_, wa, wb);
  wall_contacts_.rebuild(std::move(wa), std::move(wb), friction_, n, false);
  a_side_.assign(bodies_.size(), Wrench{Vec3::Zero(), Vec3::Zero()});

  ball_contacts_.record_build_gaps(balls_.position, balls_.radius);
  reference_positions_ = balls_.position;
  shift_since_build_ = 0.0;
  scale_at_build_ = size_scale_;
  needs_rebuild_ = false;
  wall_reference_.resize(walls_.size());
  for (Index w = 0; w < Index(walls_.size()); ++w) wall_reference_[w] = walls_[w].displacement;
  ++builds_;
  rebuild_policy_.start(n, ball_contacts_.size());
  if (prepared_ && !settings_.fixed_dt) update_timestep();
}

void Simulation::run(long steps) {
  for (long k = 0; k < steps; ++k) step();
}

EnergyBudget Simulation::energy() const {
  EnergyBudget e = energy_budget(balls_, bodies_, materials_, walls_, ball_contacts_,
                                 wall_contacts_, wall_work_, law_);
  if (!settings_.energy_ledger) e.drop_work();
  return e;
}

ContactStats Simulation::contacts() const {
  return contact_stats(bodies_, ball_contacts_, wall_contacts_);
}

double Simulation::unbalanced_force_ratio() const {
  return ballast::unbalanced_force_ratio(bodies_, ball_contacts_, wall_contacts_);
}

}  // namespace ballast
