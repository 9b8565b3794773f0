#include "cases/cycle_recorder.hpp"

#include <algorithm>
#include <cmath>

#include "cases/contact_census.hpp"
#include "engine/porosity.hpp"

namespace ballast {

std::vector<long> snapshot_cycles_of(const BoxTestScene& s) {
  std::vector<long> out = s.snapshot_cycles;
  if (out.empty()) {
    for (long n = 1; n <= s.cycles; n *= 10) out.push_back(n);
    out.push_back(s.cycles);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double settlement_log_slope(const std::vector<double>& trough) {
  const std::size_t n = trough.size();
  if (n < 2) return 0.0;
  // Ordinary least squares of s on x = log10(cycle), summed in cycle order.
  double sx = 0.0, sy = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    sx += std::log10(double(k + 1));
    sy += trough[k];
  }
  const double mx = sx / double(n), my = sy / double(n);
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double dx = std::log10(double(k + 1)) - mx;
    sxy += dx * (trough[k] - my);
    sxx += dx * dx;
  }
  return sxy / sxx;
}

CycleRecorder::CycleRecorder(const BoxTestScene& s, const Simulation& sim, Index wall, Index servo,
                             double x0, double x1)
    : wall_(wall),
      servo_(servo),
      x0_(x0),
      x1_(x1),
      width_(s.width),
      cube_side_(s.cube_side),
      t0_(sim.time()),
      period_(1.0 / s.frequency),
      z0_(sim.walls()[wall].displacement.z()),
      last_force_(sim.servos()[servo].measured_force),
      snapshots_(snapshot_cycles_of(s)) {}

double CycleRecorder::settlement(const Simulation& sim) const {
  return z0_ - sim.walls()[wall_].displacement.z();
}

void CycleRecorder::after_step(const Simulation& sim, CycleRecords& out) {
  // The work the sleeper does on the bed, ∫F dδ by the trapezoid rule: F is the
  // bed's reaction on the sleeper (N, up), δ the settlement (m, down).
  const double force = sim.servos()[servo_].measured_force, now = settlement(sim);
  work_ += 0.5 * (force + last_force_) * (now - last_settlement_);
  last_force_ = force;
  last_settlement_ = now;
  // Cycle n peaks at t0 + (n − ½)/f and ends at t0 + n/f: computed from n, not
  // accumulated, so that the last cycle ends exactly where the load loop stops.
  if (!peak_passed_ && sim.time() >= t0_ + (double(cycle_) - 0.5) * period_) {
    peak_passed_ = true;
    out.settlement_peak.push_back(now);
    const SleeperBearing b = sleeper_bearing(sim, wall_);
    out.sleeper_contacts.push_back(b.contacts);
    out.sleeper_bodies.push_back(b.bodies);
  }
  if (peak_passed_ && sim.time() >= t0_ + double(cycle_) * period_) end_cycle(sim, out);
}

void CycleRecorder::end_cycle(const Simulation& sim, CycleRecords& out) {
  constexpr double kDeg = 180.0 / kPi;
  const double now = settlement(sim);
  out.settlement_trough.push_back(now);
  out.sleeper_work.push_back(work_);
  const std::vector<Vec3>& rotation = sim.bodies().rotation;
  double sum = 0.0;
  for (const Vec3& r : rotation) sum += r.norm() * kDeg;
  out.rotation_mean_deg.push_back(rotation.empty() ? 0.0 : sum / double(rotation.size()));
  // The column under the sleeper, from the base to the sleeper's underside now.
  const double z_top = sim.walls()[wall_].lo.z();
  out.porosity_under.push_back(z_top > 0.0 ? grid_porosity(sim.balls(), Vec3(x0_, 0.0, 0.0),
                                                           Vec3(x1_, width_, z_top), cube_side_)
                                                 .porosity
                                           : 0.0);
  if (sampling_series()) {
    CycleSnapshot snap;
    snap.cycle = cycle_;
    snap.settlement = now;
    snap.position = sim.bodies().position;
    snap.rotation_deg.reserve(rotation.size());
    for (const Vec3& r : rotation) snap.rotation_deg.push_back(r.norm() * kDeg);
    out.snapshots.push_back(std::move(snap));
    ++next_snapshot_;
  }
  work_ = 0.0;
  peak_passed_ = false;
  ++cycle_;
}

}  // namespace ballast
