#include "study/cli/run_summary.hpp"

#include <cstdio>
#include <ostream>

#include "cases/cycle_recorder.hpp"

namespace ballast {

namespace {

nlohmann::json contacts_json(const ContactSnapshot& c) {
  return {{"ball_contacts", c.stats.ball_contacts},
          {"wall_contacts", c.stats.wall_contacts},
          {"coordination", c.stats.coordination},
          {"max_force_N", c.stats.max_force},
          {"mean_force_N", c.stats.mean_force}};
}

nlohmann::json rotation_json(const RotationStats& s) {
  return {{"mean_deg", s.mean_deg}, {"max_deg", s.max_deg}};
}

}  // namespace

nlohmann::json run_summary_json(const BoxTestResult& r) {
  nlohmann::json stages = nlohmann::json::array();
  for (const StageReport& s : r.stages)
    stages.push_back({{"name", s.name},
                      {"steps", s.steps},
                      {"simulated_s", s.simulated},
                      {"seconds", s.seconds},
                      {"unbalanced", s.unbalanced},
                      {"settled", s.settled()},
                      {"ended_by", s.what_ended()},
                      {"energy_in_J", s.energy_in},
                      {"energy_dissipated_J", s.energy_dissipated},
                      {"energy_error_J", s.energy_error}});
  nlohmann::json j = {{"scene", r.scene_name},
                      {"bodies", r.bodies},
                      {"balls", r.balls},
                      {"dt_s", r.dt},
                      {"dt_critical_s", r.dt_critical},
                      {"wall_seconds", r.wall_seconds},
                      {"loaded", r.loaded},
                      {"porosity_grid", r.porosity_grid},
                      {"porosity_grid_interior", r.porosity_grid_interior},
                      {"porosity_spheres", r.porosity_spheres},
                      {"bed_height_m", r.bed_height},
                      {"contacts_before", contacts_json(r.before)},
                      {"rotation_cycle", rotation_json(r.rotation_cycle)},
                      {"energy_balance_J", r.energy.balance()},
                      {"stages", stages}};
  if (r.loaded) {
    j["contacts_peak"] = contacts_json(r.at_peak);
    j["contacts_after"] = contacts_json(r.after);
    j["rotation_loading"] = rotation_json(r.rotation_loading);
    j["rotation_unloading"] = rotation_json(r.rotation_unloading);
    j["max_displacement_peak_m"] = r.max_displacement_peak;
    j["max_displacement_after_m"] = r.max_displacement_after;
    j["settlement_peak_m"] = r.settlement_peak;
    j["permanent_settlement_m"] = r.permanent_settlement;
    j["resilient_settlement_m"] = r.resilient_settlement;
    j["max_force_error_N"] = r.max_force_error;
    j["rms_force_error_N"] = r.rms_force_error;
    j["cycles"] = r.cycles.count();
    j["settlement_log_slope_m"] = settlement_log_slope(r.cycles.settlement_trough);
  }
  return j;
}

void print_run_summary(std::ostream& out, const BoxTestResult& r) {
  char line[200];
  out << "\n"
      << r.scene_name << ": " << r.bodies << " bodies, " << r.balls << " balls, dt " << r.dt
      << " s (critical " << r.dt_critical << " s), " << r.wall_seconds << " s wall\n";
  out << "porosity under the sleeper (5 mm grid): " << r.porosity_grid
      << "; one diameter inside the walls, base and top: " << r.porosity_grid_interior << "\n";
  std::snprintf(line, sizeof line, "%-16s %9s %9s %6s %10s %10s\n", "contacts", "ball-ball",
                "ball-wall", "Z", "max F (N)", "mean F (N)");
  out << line;
  const std::pair<const char*, const ContactSnapshot*> rows[] = {
      {"before loading", &r.before}, {"at peak load", &r.at_peak}, {"after unloading", &r.after}};
  for (const auto& [name, c] : rows) {
    if (!r.loaded && c != &r.before) continue;
    std::snprintf(line, sizeof line, "%-16s %9ld %9ld %6.2f %10.1f %10.2f\n", name,
                  c->stats.ball_contacts, c->stats.wall_contacts, c->stats.coordination,
                  c->stats.max_force, c->stats.mean_force);
    out << line;
  }
  if (!r.loaded) return;
  std::snprintf(line, sizeof line,
                "rotation (deg) mean/max: loading %.3f/%.2f, unloading %.3f/%.2f, cycle "
                "%.3f/%.2f\n",
                r.rotation_loading.mean_deg, r.rotation_loading.max_deg,
                r.rotation_unloading.mean_deg, r.rotation_unloading.max_deg,
                r.rotation_cycle.mean_deg, r.rotation_cycle.max_deg);
  out << line;
  std::snprintf(line, sizeof line,
                "max displacement: %.2f mm at peak, %.2f mm after the cycle\n"
                "sleeper settlement: %.3f mm at peak, permanent %.3f mm, resilient %.3f mm\n"
                "sleeper force vs target: max error %.0f N, rms %.0f N\n",
                r.max_displacement_peak * 1e3, r.max_displacement_after * 1e3,
                r.settlement_peak * 1e3, r.permanent_settlement * 1e3, r.resilient_settlement * 1e3,
                r.max_force_error, r.rms_force_error);
  out << line;
  const CycleRecords& c = r.cycles;
  if (c.count() < 2) return;
  // The figures above span all cycles from the first peak on; the per-cycle view:
  std::snprintf(line, sizeof line,
                "%zu cycles: permanent settlement %.3f mm after cycle 1, %.3f mm after the last "
                "(%.3f mm per decade of cycles, least squares on log10 N); last rebound %.3f mm\n",
                c.count(), c.settlement_trough.front() * 1e3, c.settlement_trough.back() * 1e3,
                settlement_log_slope(c.settlement_trough) * 1e3, r.resilient_settlement * 1e3);
  out << line;
}

}  // namespace ballast
